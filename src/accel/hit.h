// Result of tracing one ray (20 bytes): enough to rebuild the surface later.
#pragma once
#include <cstdint>

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

// Rays as structure of arrays, the form the SIMD kernels take (arrays, not vectors, cross the dispatch seam).
struct RaySoA {
  const float *ox, *oy, *oz;
  const float *dx, *dy, *dz;
  const float* t_max;
};

}  // namespace torte
