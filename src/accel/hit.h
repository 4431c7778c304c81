// Result of tracing one ray (20 bytes): enough to rebuild the surface later.
#pragma once
#include <cstdint>

#include "core/ray.h"
#include "core/vec.h"

namespace torte {

constexpr uint32_t kNoHit = 0xffffffffu;

struct Hit {
  float t = kInfinity;
  uint32_t prim = kNoHit;  // primitive id as the traced structure numbers them (kNoHit for a miss)
  float b1 = 0, b2 = 0;    // triangle barycentrics of vertices 1 and 2, or a quadric's (u, v)
  uint32_t instance = kNoHit;  // scene level: the instance the primitive was hit in (kNoHit: not instanced)
};
static_assert(sizeof(Hit) == 20);

/// The traversal kernel a batch of rays takes: one ray at a time (the SIMD lanes test a node's children), or
/// packets of 8 or 16 neighbouring rays (the lanes are rays). The render loop traces a tile's camera rays as
/// kPacket8 and everything else as kSingle; torte.bench times each on any scene.
enum class TraceKernel : uint8_t { kSingle = 0, kPacket8 = 8, kPacket16 = 16 };

// Rays as structure of arrays, the form the SIMD kernels take (arrays, not vectors, cross the dispatch seam).
struct RaySoA {
  const float *ox, *oy, *oz;
  const float *dx, *dy, *dz;
  const float* t_max;
};

// Ray i of a RaySoA (for the code that traces one ray at a time), with t_max replaced when given.
inline Ray ray_at(const RaySoA& rays, size_t i) {
  return Ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}, rays.t_max[i]};
}
inline Ray ray_at(const RaySoA& rays, size_t i, float t_max) {
  Ray r = ray_at(rays, i);
  r.t_max = t_max;
  return r;
}

/// One ray stored so that soa() views it as a RaySoA of count 1 (the single-ray entry points over the batch ones).
struct SingleRay {
  float v[7];
  explicit SingleRay(const Ray& r) : v{r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.t_max} {}
  RaySoA soa() const { return {&v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6]}; }
};

}  // namespace torte
