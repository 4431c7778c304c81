// Scalar reference traversal of WideBvh<N> (plain C++, one ray at a time): the ground truth the SIMD kernels
// in simd/ are tested against, and a readable statement of what they must compute.
//
// Primitive numbering: the callbacks and Hit::prim use the *leaf-order* index i (a position in prim_indices and
// in TriangleLeaves), which is what the kernels report and, for a mesh reordered into leaf order, the mesh's own
// triangle index. bvh.prim_indices[i] is the caller's original primitive index.
//
// Child boxes are tested exactly as the reference BVH2 does (SlabRay::hits: near/far planes by direction sign,
// conservative far-plane rounding, NaN slabs ignored). Empty slots (lo = +inf, hi = -inf) are skipped; the slab
// test would miss them anyway, which the kernels rely on.
#pragma once
#include <cstdint>
#include <type_traits>

#include "accel/bvh2.h"
#include "accel/bvh_build.h"
#include "accel/hit.h"
#include "accel/wide_bvh.h"
#include "core/ray.h"
#include "geometry/triangle.h"

namespace torte {

template <int N>
Bounds3f wide_child_bounds(const WideNode<N>& n, int i) {
  return {{n.lo_x[i], n.lo_y[i], n.lo_z[i]}, {n.hi_x[i], n.hi_y[i], n.hi_z[i]}};
}

// Calls a primitive callback as (i, ray) or, if it takes them, (i, ray, first, count) with the leaf's range
// (TriangleLeaves are laid out per leaf).
template <class F, class R>
bool call_prim(F& f, uint32_t i, R& ray, uint32_t first, uint32_t count) {
  if constexpr (std::is_invocable_v<F&, uint32_t, R&, uint32_t, uint32_t>) return f(i, ray, first, count);
  else return f(i, ray);
}

// Closest hit. `hit_prim(i, ray)` tests leaf-order primitive i; on a hit closer than ray.t_max it must shrink
// ray.t_max and return true. Children are visited near to far by slab entry distance, and popped entries that
// now lie beyond the closest hit are skipped. Returns true if anything was hit. `cost` (optional): adds the nodes
// visited and the primitives of the leaves reached, as the counting kernels do (traverse.h).
template <int N, class HitPrim>
bool wide_intersect(const WideBvh<N>& bvh, Ray& ray, HitPrim&& hit_prim, TraversalCost* cost = nullptr) {
  if (bvh.nodes.empty()) return false;
  const SlabRay slab(ray);
  struct Entry {
    uint32_t child;  // node index, or kLeafFlag | first primitive
    uint32_t count;  // leaf primitives
    float t_near;
  };
  // Each level leaves at most N - 1 siblings on the stack and the depth is at most kMaxBvhDepth.
  Entry stack[kWideStackSize<N>];
  int sp = 0;
  stack[sp++] = {0, 0, 0.0f};
  bool hit = false;
  while (sp > 0) {
    const Entry e = stack[--sp];
    if (e.t_near > ray.t_max) continue;
    if (e.child & kLeafFlag) {
      const uint32_t first = e.child & ~kLeafFlag;
      if (cost) cost->prims += e.count;
      for (uint32_t i = 0; i < e.count; ++i) hit |= call_prim(hit_prim, first + i, ray, first, e.count);
      continue;
    }
    if (cost) ++cost->nodes;
    const WideNode<N>& n = bvh.nodes[e.child];
    Entry found[N];
    int k = 0;
    for (int i = 0; i < N; ++i) {
      float t;
      if (n.child[i] == kEmptyChild || !slab.hits(wide_child_bounds(n, i), ray.t_max, &t)) continue;
      // Insertion sort, farthest first, so the nearest child is pushed last and popped next.
      int j = k++;
      for (; j > 0 && found[j - 1].t_near < t; --j) found[j] = found[j - 1];
      found[j] = {n.child[i], n.leaf_count[i], t};
    }
    for (int i = 0; i < k; ++i) stack[sp++] = found[i];
  }
  return hit;
}

// Any hit: `occluded_prim(i, ray)` returns true if leaf-order primitive i blocks the ray in (0, ray.t_max).
// No ordering: the first blocker ends the search.
template <int N, class OccludedPrim>
bool wide_occluded(const WideBvh<N>& bvh, const Ray& ray, OccludedPrim&& occluded_prim) {
  if (bvh.nodes.empty()) return false;
  const SlabRay slab(ray);
  struct Entry {
    uint32_t child, count;
  };
  Entry stack[kWideStackSize<N>];
  int sp = 0;
  stack[sp++] = {0, 0};
  while (sp > 0) {
    const Entry e = stack[--sp];
    if (e.child & kLeafFlag) {
      const uint32_t first = e.child & ~kLeafFlag;
      for (uint32_t i = 0; i < e.count; ++i)
        if (call_prim(occluded_prim, first + i, ray, first, e.count)) return true;
      continue;
    }
    const WideNode<N>& n = bvh.nodes[e.child];
    for (int i = 0; i < N; ++i)
      if (n.child[i] != kEmptyChild && slab.hits(wide_child_bounds(n, i), ray.t_max))
        stack[sp++] = {n.child[i], n.leaf_count[i]};
  }
  return false;
}

// Leaf-order triangle i of the leaf (first, count).
inline void leaf_triangle(const TriangleLeaves& l, uint32_t first, uint32_t count, uint32_t i, Vec3f* p0, Vec3f* p1,
                          Vec3f* p2) {
  *p0 = l.vertex(first, count, i, 0);
  *p1 = l.vertex(first, count, i, 1);
  *p2 = l.vertex(first, count, i, 2);
}

// Closest triangle hit in (0, ray.t_max) with torte::intersect_triangle (watertight). Hit::prim is the
// leaf-order index (kNoHit for a miss); bvh.prim_indices[hit.prim] is the original triangle.
// `cost` (optional): as wide_intersect's.
template <int N>
Hit wide_closest_hit_reference(const WideBvh<N>& bvh, const TriangleLeaves& leaves, const Ray& ray,
                               TraversalCost* cost = nullptr) {
  Hit hit;
  const WatertightRay wr(ray);
  Ray r = ray;
  wide_intersect(bvh, r, [&](uint32_t i, Ray& rr, uint32_t first, uint32_t count) {
    Vec3f p0, p1, p2;
    leaf_triangle(leaves, first, count, i, &p0, &p1, &p2);
    TriangleHit th;
    if (!intersect_triangle(wr, rr.t_max, p0, p1, p2, &th)) return false;
    rr.t_max = th.t;
    hit = {th.t, i, th.b1, th.b2};
    return true;
  }, cost);
  return hit;
}

// True if any triangle blocks the ray in (0, ray.t_max).
template <int N>
bool wide_any_hit_reference(const WideBvh<N>& bvh, const TriangleLeaves& leaves, const Ray& ray) {
  const WatertightRay wr(ray);
  return wide_occluded(bvh, ray, [&](uint32_t i, const Ray& r, uint32_t first, uint32_t count) {
    Vec3f p0, p1, p2;
    leaf_triangle(leaves, first, count, i, &p0, &p1, &p2);
    return intersect_triangle(wr, r.t_max, p0, p1, p2, nullptr);
  });
}

}  // namespace torte
