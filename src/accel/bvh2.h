// Reference binary BVH (scalar): binned SAH build over arbitrary primitive bounds, and closest-hit / any-hit
// traversal that calls back into the caller's primitive test. The SIMD wide BVH replaces it in the hot path
// later; this one stays as the reference for tests and benchmarks.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/hit.h"
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

// A ray prepared for many slab tests: reciprocal direction and, per axis, which box side is entered first.
struct SlabRay {
  Vec3f o, inv_d;
  bool neg[3];
  explicit SlabRay(const Ray& r) : o(r.o), inv_d(1 / r.d.x, 1 / r.d.y, 1 / r.d.z) {
    neg[0] = inv_d.x < 0;
    neg[1] = inv_d.y < 0;
    neg[2] = inv_d.z < 0;
  }
  // Same result as Bounds3f::intersect (including its conservative far-plane rounding), without the loop and
  // swaps: near and far planes are picked by the direction's sign.
  bool hits(const Bounds3f& b, float t_max, float* t_near = nullptr) const {
    constexpr float kRound = 1 + 2 * 3 * 0x1p-24f;
    const float tx0 = ((neg[0] ? b.hi.x : b.lo.x) - o.x) * inv_d.x;
    const float tx1 = ((neg[0] ? b.lo.x : b.hi.x) - o.x) * inv_d.x * kRound;
    const float ty0 = ((neg[1] ? b.hi.y : b.lo.y) - o.y) * inv_d.y;
    const float ty1 = ((neg[1] ? b.lo.y : b.hi.y) - o.y) * inv_d.y * kRound;
    const float tz0 = ((neg[2] ? b.hi.z : b.lo.z) - o.z) * inv_d.z;
    const float tz1 = ((neg[2] ? b.lo.z : b.hi.z) - o.z) * inv_d.z * kRound;
    // "x > t ? x : t" keeps t when x is NaN (0 * inf: a ray lying in a slab plane), so such a slab does not
    // constrain the interval, exactly as in Bounds3f::intersect.
    float t0 = 0, t1 = t_max;
    t0 = tx0 > t0 ? tx0 : t0;
    t0 = ty0 > t0 ? ty0 : t0;
    t0 = tz0 > t0 ? tz0 : t0;
    t1 = tx1 < t1 ? tx1 : t1;
    t1 = ty1 < t1 ? ty1 : t1;
    t1 = tz1 < t1 ? tz1 : t1;
    if (t_near) *t_near = t0;
    return t0 <= t1;
  }
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
  // ray.t_max and return true. Returns true if anything was hit. `cost` (optional): adds the inner nodes visited
  // and the primitives tested.
  template <class HitPrim>
  bool intersect(Ray& ray, HitPrim&& hit_prim, TraversalCost* cost = nullptr) const;
  // Any hit: `occluded_prim(prim, ray)` returns true if the primitive blocks the ray in (0, ray.t_max).
  template <class OccludedPrim>
  bool occluded(const Ray& ray, OccludedPrim&& occluded_prim) const;

 private:
  std::vector<Bvh2Node> nodes_;
  std::vector<uint32_t> prims_;
};

template <class HitPrim>
bool Bvh2::intersect(Ray& ray, HitPrim&& hit_prim, TraversalCost* cost) const {
  if (nodes_.empty()) return false;
  const SlabRay slab(ray);
  float root_near;
  if (!slab.hits(nodes_[0].bounds, ray.t_max, &root_near)) return false;
  // Both children are tested at their parent: the nearer is visited next, the farther is pushed with its entry
  // distance, and popped entries that now lie beyond the closest hit are skipped.
  struct Entry {
    uint32_t node;
    float t_near;
  };
  Entry stack[64];
  int sp = 0;
  uint32_t node = 0;
  bool hit = false;
  for (;;) {
    const Bvh2Node& n = nodes_[node];
    if (cost) {
      if (n.count > 0) cost->prims += n.count;
      else ++cost->nodes;
    }
    if (n.count > 0) {
      for (uint32_t i = 0; i < n.count; ++i) hit |= hit_prim(prims_[n.offset + i], ray);
    } else {
      const uint32_t left = node + 1, right = n.offset;
      float t_left, t_right;
      const bool hit_left = slab.hits(nodes_[left].bounds, ray.t_max, &t_left);
      const bool hit_right = slab.hits(nodes_[right].bounds, ray.t_max, &t_right);
      if (hit_left && hit_right) {
        if (t_left <= t_right) {
          stack[sp++] = {right, t_right};
          node = left;
        } else {
          stack[sp++] = {left, t_left};
          node = right;
        }
        continue;
      }
      if (hit_left || hit_right) {
        node = hit_left ? left : right;
        continue;
      }
    }
    // Pop the next subtree that can still hold a closer hit.
    for (;;) {
      if (sp == 0) return hit;
      const Entry e = stack[--sp];
      if (e.t_near <= ray.t_max) {
        node = e.node;
        break;
      }
    }
  }
}

template <class OccludedPrim>
bool Bvh2::occluded(const Ray& ray, OccludedPrim&& occluded_prim) const {
  if (nodes_.empty()) return false;
  const SlabRay slab(ray);
  if (!slab.hits(nodes_[0].bounds, ray.t_max)) return false;
  uint32_t stack[64];
  int sp = 0;
  uint32_t node = 0;
  for (;;) {
    const Bvh2Node& n = nodes_[node];
    if (n.count > 0) {
      for (uint32_t i = 0; i < n.count; ++i)
        if (occluded_prim(prims_[n.offset + i], ray)) return true;
    } else {
      // Any hit ends the search, so no ordering: just skip children the ray misses.
      const uint32_t left = node + 1, right = n.offset;
      const bool hit_left = slab.hits(nodes_[left].bounds, ray.t_max);
      const bool hit_right = slab.hits(nodes_[right].bounds, ray.t_max);
      if (hit_left) {
        if (hit_right) stack[sp++] = right;
        node = left;
        continue;
      }
      if (hit_right) {
        node = right;
        continue;
      }
    }
    if (sp == 0) return false;
    node = stack[--sp];
  }
}

}  // namespace torte
