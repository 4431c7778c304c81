// Ray-triangle intersection (watertight: Woop, Benthin & Wald 2013) and triangle helpers.
#pragma once
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
  explicit WatertightRay(const Ray& ray);
};

// Hits with 0 < t < ray.t_max only. Rays through shared edges/vertices of a closed mesh never slip through.
bool intersect_triangle(const Ray& ray, Vec3f p0, Vec3f p1, Vec3f p2, TriangleHit* hit);
// Same test with the per-ray part precomputed; `t_max` overrides the one captured in wr.
bool intersect_triangle(const WatertightRay& wr, float t_max, Vec3f p0, Vec3f p1, Vec3f p2, TriangleHit* hit);

inline float triangle_area(Vec3f p0, Vec3f p1, Vec3f p2) { return 0.5f * length(cross(p1 - p0, p2 - p0)); }

}  // namespace torte
