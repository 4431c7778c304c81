// Axis-aligned bounding box (24 bytes) and the slab test used by the reference BVH2.
#pragma once
#include "core/vec.h"

namespace torte {

struct Bounds3f {
  Vec3f lo{kInfinity, kInfinity, kInfinity};
  Vec3f hi{-kInfinity, -kInfinity, -kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(Vec3f p) { lo = min(lo, p); hi = max(hi, p); }
  void extend(const Bounds3f& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
  Vec3f diagonal() const { return hi - lo; }
  Vec3f center() const { return (lo + hi) * 0.5f; }
  float surface_area() const {
    if (empty()) return 0;
    const Vec3f d = diagonal();
    return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
  bool contains(Vec3f p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  // Slab test with a precomputed reciprocal direction; returns true when [t0,t1] overlaps the box.
  bool intersect(Vec3f o, Vec3f inv_d, float t_max, float* t_near = nullptr) const {
    float t0 = 0, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
      float tn = (lo[a] - o[a]) * inv_d[a];
      float tf = (hi[a] - o[a]) * inv_d[a];
      if (tn > tf) std::swap(tn, tf);
      // Conservative rounding (pbrt's gamma(3) factor) so grazing rays never miss a box they touch.
      tf *= 1 + 2 * 3 * 0x1p-24f;
      t0 = tn > t0 ? tn : t0;
      t1 = tf < t1 ? tf : t1;
      if (t0 > t1) return false;
    }
    if (t_near) *t_near = t0;
    return true;
  }
};

inline Bounds3f merge(Bounds3f a, const Bounds3f& b) { a.extend(b); return a; }

}  // namespace torte
