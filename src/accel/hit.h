// Result of tracing one ray (20 bytes): enough to rebuild the surface later.
#pragma once
#include <cstdint>
#include <vector>

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

/// The work one ray's closest-hit search did, for the traversal_cost AOV (render/aov_pass.h): `nodes`, the
/// acceleration nodes it visited (wide BVH nodes, BVH2 nodes of quadrics and instances, kd-tree nodes of voxel
/// grids); `prims`, the primitives it tested (the triangles of every leaf it reached, quadrics, the instances whose
/// boxes it entered, solid voxels and the cells of cell shapes).
struct TraversalCost {
  uint32_t nodes = 0, prims = 0;
};

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

/// Rays owned as structure of arrays, for code that builds a batch ray by ray (benchmark workloads, torte.bench,
/// the continuations of rays past cut-outs); soa() is the view the kernels take.
struct RayArrays {
  std::vector<float> ox, oy, oz, dx, dy, dz, t_max;
  size_t size() const { return ox.size(); }
  void push(const Ray& r) {
    ox.push_back(r.o.x), oy.push_back(r.o.y), oz.push_back(r.o.z);
    dx.push_back(r.d.x), dy.push_back(r.d.y), dz.push_back(r.d.z);
    t_max.push_back(r.t_max);
  }
  void clear() {
    for (std::vector<float>* v : {&ox, &oy, &oz, &dx, &dy, &dz, &t_max}) v->clear();
  }
  Ray ray(size_t i) const { return {{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, t_max[i]}; }
  // View of rays [offset, size()).
  RaySoA soa(size_t offset = 0) const {
    return {ox.data() + offset, oy.data() + offset, oz.data() + offset, dx.data() + offset,
            dy.data() + offset, dz.data() + offset, t_max.data() + offset};
  }
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
