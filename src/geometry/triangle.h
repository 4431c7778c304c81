// Ray-triangle intersection (watertight: Woop, Benthin & Wald 2013) and triangle helpers.
#pragma once
#include <cmath>

#include "core/ray.h"
#include "core/vec.h"

namespace torte {

struct TriangleHit {
  float t;
  float b1, b2;  // barycentrics of p1 and p2; p = (1-b1-b2) p0 + b1 p1 + b2 p2
};

// The per-ray part of the watertight test (axis permutation and shear), computed once per ray rather than once
// per triangle.
struct WatertightRay {
  Vec3f o;
  int kx, ky, kz;
  float sx, sy, sz;
  float t_max;
  bool valid;  // false for a zero or NaN direction
  WatertightRay() = default;  // for callers that fill the fields from precomputed values
  explicit WatertightRay(const Ray& ray);
};

// Inline and free of branches: every traversal kernel builds one per ray, and with random directions the
// branches of max_dimension and of the swap below mispredicted often enough to cost ~8 % of diffuse-ray traversal
// (perf, 2026-11-22). One division: the shear's sx and sy are products with sz = 1 / d[kz] (the kernels take sz
// from the slab test's 1 / d, so a 16-ray set-up saves two vector divisions; 2026-11-23). No sums, so
// floating-point contraction cannot change it.
inline WatertightRay::WatertightRay(const Ray& ray) : o(ray.o), t_max(ray.t_max) {
  const float d[3] = {ray.d.x, ray.d.y, ray.d.z};
  // kz = max_dimension(abs(d)) (ties and NaN resolve the same way), as conditional moves.
  const float ax = std::fabs(d[0]), ay = std::fabs(d[1]), az = std::fabs(d[2]);
  const bool x_over_y = ax > ay;
  const float axy = x_over_y ? ax : ay;
  kz = axy > az ? (x_over_y ? 0 : 1) : 2;
  // kx, ky follow kz cyclically; swapping them for a negative d[kz] keeps the winding, which only matters for the
  // sign of det (both faces count here, so it is cosmetic but cheap).
  const int next_x = kz == 2 ? 0 : kz + 1;
  const int next_y = next_x == 2 ? 0 : next_x + 1;
  const float dz = d[kz];
  const bool flip = dz < 0;
  kx = flip ? next_y : next_x;
  ky = flip ? next_x : next_y;
  valid = dz != 0;  // false for a zero (or NaN) direction
  sz = 1.0f / dz;
  sx = d[kx] * sz;
  sy = d[ky] * sz;
}

// Hits with 0 < t < ray.t_max only. Rays through shared edges/vertices of a closed mesh never slip through.
bool intersect_triangle(const Ray& ray, Vec3f p0, Vec3f p1, Vec3f p2, TriangleHit* hit);
// Same test with the per-ray part precomputed; `t_max` overrides the one captured in wr.
bool intersect_triangle(const WatertightRay& wr, float t_max, Vec3f p0, Vec3f p1, Vec3f p2, TriangleHit* hit);

inline float triangle_area(Vec3f p0, Vec3f p1, Vec3f p2) { return 0.5f * length(cross(p1 - p0, p2 - p0)); }

}  // namespace torte
