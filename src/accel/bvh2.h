// Reference binary BVH (scalar): binned SAH build over arbitrary primitive bounds, and closest-hit / any-hit
// traversal that calls back into the caller's primitive test. The SIMD wide BVH replaces it in the hot path
// later; this one stays as the reference for tests and benchmarks.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"

namespace torte {

// 32 bytes, two per cache line. Interior: `offset` is the index of the second child (the first child follows
// the node directly), count == 0. Leaf: primitives prim_indices[offset, offset + count).
struct Bvh2Node {
  Bounds3f bounds;
  uint32_t offset;
  uint16_t count;
  uint8_t axis;  // split axis of an interior node: traversal visits the near child first
  uint8_t pad;
};
static_assert(sizeof(Bvh2Node) == 32);

struct Bvh2BuildOptions {
  int max_leaf_size = 4;
  int bins = 16;
  float traversal_cost = 1.0f;  // relative to one primitive test
};

class Bvh2 {
 public:
  Bvh2() = default;
  // Builds over primitives 0..n-1 given their bounds (empty bounds are allowed and never hit).
  void build(std::span<const Bounds3f> prim_bounds, const Bvh2BuildOptions& options = {});

  const std::vector<Bvh2Node>& nodes() const { return nodes_; }
  const std::vector<uint32_t>& prim_indices() const { return prims_; }
  Bounds3f bounds() const { return nodes_.empty() ? Bounds3f{} : nodes_[0].bounds; }
  // SAH cost of the tree (node traversal cost + primitive cost, weighted by area relative to the root).
  float sah_cost(float traversal_cost = 1.0f) const;

  // Closest hit. `hit_prim(prim, ray)` tests one primitive; on a hit closer than ray.t_max it must shrink
  // ray.t_max and return true. Returns true if anything was hit.
  template <class HitPrim>
  bool intersect(Ray& ray, HitPrim&& hit_prim) const;
  // Any hit: `occluded_prim(prim, ray)` returns true if the primitive blocks the ray in (0, ray.t_max).
  template <class OccludedPrim>
  bool occluded(const Ray& ray, OccludedPrim&& occluded_prim) const;

 private:
  std::vector<Bvh2Node> nodes_;
  std::vector<uint32_t> prims_;
};

template <class HitPrim>
bool Bvh2::intersect(Ray& ray, HitPrim&& hit_prim) const {
  if (nodes_.empty()) return false;
  const Vec3f inv_d{1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z};
  const bool neg[3] = {inv_d.x < 0, inv_d.y < 0, inv_d.z < 0};
  uint32_t stack[64];
  int sp = 0;
  uint32_t node = 0;
  bool hit = false;
  for (;;) {
    const Bvh2Node& n = nodes_[node];
    if (n.bounds.intersect(ray.o, inv_d, ray.t_max)) {
      if (n.count > 0) {
        for (uint32_t i = 0; i < n.count; ++i) hit |= hit_prim(prims_[n.offset + i], ray);
      } else {
        // Visit the child on the ray's near side of the split first.
        if (neg[n.axis]) {
          stack[sp++] = node + 1;
          node = n.offset;
        } else {
          stack[sp++] = n.offset;
          node = node + 1;
        }
        continue;
      }
    }
    if (sp == 0) break;
    node = stack[--sp];
  }
  return hit;
}

template <class OccludedPrim>
bool Bvh2::occluded(const Ray& ray, OccludedPrim&& occluded_prim) const {
  if (nodes_.empty()) return false;
  const Vec3f inv_d{1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z};
  uint32_t stack[64];
  int sp = 0;
  uint32_t node = 0;
  for (;;) {
    const Bvh2Node& n = nodes_[node];
    if (n.bounds.intersect(ray.o, inv_d, ray.t_max)) {
      if (n.count > 0) {
        for (uint32_t i = 0; i < n.count; ++i)
          if (occluded_prim(prims_[n.offset + i], ray)) return true;
      } else {
        stack[sp++] = n.offset;
        node = node + 1;
        continue;
      }
    }
    if (sp == 0) break;
    node = stack[--sp];
  }
  return false;
}

}  // namespace torte
