// Single-ray traversal of WideBvh<N> + TriangleLeaves, per Highway target: the kernel of traverse.cc, also used
// by traverse_packet.cc for subtrees where too few rays of a packet stay active. Include it after
// traverse-inl.h inside a file compiled with foreach_target and without FMA contraction (see traverse.cc).
// Nodes: lanes = children. One slab test per axis covers all N children (CappedTag<float, N>; targets narrower
// than N loop over lane groups); near/far planes are picked per ray by the direction's signs. The slab distance
// of a plane is one fused multiply-add with a per-ray margin that keeps the test conservative (kSlabMargin in
// traverse-inl.h: 1 to 5 % faster on diffuse rays, 2026-11-22); rays with a zero or tiny direction component take
// SlabRay::hits of accel/bvh2.h instead, with the far rounding folded into the inverse direction. Hit
// children are sorted far to near and pushed, and the nearest is visited next; popped entries starting beyond the
// closest hit so far are skipped. The second nearest (the likeliest next pop) is prefetched when pushed: about
// +4 % on diffuse rays (2026-11-22; prefetching every pushed child, or the next stack entry at each pop, measured
// no better). The per-ray constants come from single_ray-inl.h, computed for 16 rays at a time.
// Leaves: lanes = triangles, loaded straight from the leaf's SoA runs (LoadU + FirstN), with the watertight test
// of traverse-inl.h; lanes where an edge function is exactly 0 are re-tested by the scalar intersect_triangle,
// which falls back to double precision there.

// Per-target include guard (Highway's pattern).
#if defined(TORTE_SIMD_TRAVERSE_SINGLE_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_TRAVERSE_SINGLE_INL_H_TARGET
#undef TORTE_SIMD_TRAVERSE_SINGLE_INL_H_TARGET
#else
#define TORTE_SIMD_TRAVERSE_SINGLE_INL_H_TARGET
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "accel/hit.h"
#include "accel/wide_bvh.h"
#include "geometry/triangle.h"
#include "traverse-inl.h"
#include "layout-inl.h"
#include "single_ray-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

using traverse_detail::kFarRound;
using traverse_detail::kMaxWideDepth;

// The FMA slab test of a QuantNode's 8 children with the dequantisation folded in: a plane's distance
// (origin + q scale - o) / d is fma(q, scale * r, origin * r - o * r - margin), r = 1 / d, so the node's origin and
// scale become two per-axis constants (scale * r is exact: a power of two) and each plane costs one multiply-add
// after the byte's conversion, as a WideNode's plane does; dequantising first put one more on every node's
// critical path. Conservative still: against the FMA test of the dequantised planes (traverse-inl.h,
// kSlabMargin) this rounds origin * r - org once more and the dequantised plane is the exact one rounded, at
// most u |r| (2 extent + |o|) + u margin more in all, within the margin's factor of two.
template <int N>
HWY_INLINE uint32_t IntersectQuantChildrenFma(const QuantNode& node, const SingleRay& r, float t_max,
                                              float* t_near) {
  const hn::CappedTag<float, N> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<uint8_t, decltype(d)> d8;
  const size_t L = hn::Lanes(d);
  hn::Vec<decltype(d)> sr[3], near_c[3], far_c[3];
  for (int a = 0; a < 3; ++a) {
    const auto inv = hn::Set(d, r.inv_d(a)), origin = hn::Set(d, node.origin[a]);
    sr[a] = hn::Mul(hn::Set(d, node.scale[a]), inv);
    near_c[a] = hn::MulSub(origin, inv, hn::Set(d, r.org_near(a)));
    far_c[a] = hn::MulSub(origin, inv, hn::Set(d, r.org_far(a)));
  }
  const uint8_t* const q = &node.q[0][0];
  const auto plane = [&](uint32_t off, size_t g, int a, const hn::Vec<decltype(d)>& c) {
    return hn::MulAdd(hn::ConvertTo(d, hn::PromoteTo(di, hn::LoadU(d8, q + off + g))), sr[a], c);
  };
  uint32_t bits = 0;
  for (size_t g = 0; g < size_t(N); g += L) {
    const auto tx0 = plane(r.near_off(0), g, 0, near_c[0]), ty0 = plane(r.near_off(1), g, 1, near_c[1]);
    const auto tz0 = plane(r.near_off(2), g, 2, near_c[2]), tx1 = plane(r.far_off(0), g, 0, far_c[0]);
    const auto ty1 = plane(r.far_off(1), g, 1, far_c[1]), tz1 = plane(r.far_off(2), g, 2, far_c[2]);
    const auto t0 = hn::Max(hn::Max(tx0, ty0), hn::Max(tz0, hn::Zero(d)));
    const auto t1 = hn::Min(hn::Min(tx1, ty1), hn::Min(tz1, hn::Set(d, t_max)));
    hn::StoreU(t0, d, t_near + g);
    bits |= MaskBits(d, hn::Le(t0, t1)) << g;
  }
  return bits & node.occupied;
}

// Slab test of all N children of `node` (a WideNode or a QuantNode: layout-inl.h). Returns the hit children as
// bits and their entry distances in t_near.
// kFma: one fused multiply-add per plane with the margins of the ray's constants (traverse_detail::kSlabMargin);
// otherwise subtract, then multiply, as SlabRay (rays with a zero or tiny direction component).
template <int N, bool kFma, class Node>
HWY_INLINE uint32_t IntersectChildren(const Node& node, const SingleRay& r, float t_max, float* t_near) {
  if constexpr (kFma && std::is_same_v<Node, QuantNode>) return IntersectQuantChildrenFma<N>(node, r, t_max, t_near);
  const hn::CappedTag<float, N> d;
  const size_t L = hn::Lanes(d);
  const auto ix = hn::Set(d, r.inv_d(0)), iy = hn::Set(d, r.inv_d(1)), iz = hn::Set(d, r.inv_d(2));
  uint32_t bits = 0;
  for (size_t g = 0; g < size_t(N); g += L) {
    const auto bx0 = LoadPlanes(d, node, r.near_off(0), 0, g), by0 = LoadPlanes(d, node, r.near_off(1), 1, g);
    const auto bz0 = LoadPlanes(d, node, r.near_off(2), 2, g), bx1 = LoadPlanes(d, node, r.far_off(0), 0, g);
    const auto by1 = LoadPlanes(d, node, r.far_off(1), 1, g), bz1 = LoadPlanes(d, node, r.far_off(2), 2, g);
    hn::Vec<decltype(d)> tx0, ty0, tz0, tx1, ty1, tz1;
    if constexpr (kFma) {
      tx0 = hn::MulSub(bx0, ix, hn::Set(d, r.org_near(0)));
      ty0 = hn::MulSub(by0, iy, hn::Set(d, r.org_near(1)));
      tz0 = hn::MulSub(bz0, iz, hn::Set(d, r.org_near(2)));
      tx1 = hn::MulSub(bx1, ix, hn::Set(d, r.org_far(0)));
      ty1 = hn::MulSub(by1, iy, hn::Set(d, r.org_far(1)));
      tz1 = hn::MulSub(bz1, iz, hn::Set(d, r.org_far(2)));
    } else {
      const auto ox = hn::Set(d, r.o(0)), oy = hn::Set(d, r.o(1)), oz = hn::Set(d, r.o(2));
      tx0 = hn::Mul(hn::Sub(bx0, ox), ix);
      ty0 = hn::Mul(hn::Sub(by0, oy), iy);
      tz0 = hn::Mul(hn::Sub(bz0, oz), iz);
      tx1 = hn::Mul(hn::Sub(bx1, ox), hn::Set(d, r.inv_d_far(0)));
      ty1 = hn::Mul(hn::Sub(by1, oy), hn::Set(d, r.inv_d_far(1)));
      tz1 = hn::Mul(hn::Sub(bz1, oz), hn::Set(d, r.inv_d_far(2)));
    }
    // A ray lying in a slab plane gives 0 * inf = NaN there (exact test only); that slab must not constrain the
    // interval (as in SlabRay). Max(x, acc) / Min(x, acc) return acc when x is NaN on every target (x86 min/max
    // return their second operand, HWY_SCALAR the non-NaN one), so keep the accumulator second.
    hn::Vec<decltype(d)> t0, t1;
    if constexpr (kFma) {
      // No NaN on this path (finite, non-tiny 1 / d; planes finite or infinite), so the order is free: a pairwise
      // tree is one step shorter on the traversal's critical path (+1.3 to 1.9 % on diffuse rays, AVX3,
      // 2026-11-23).
      t0 = hn::Max(hn::Max(tx0, ty0), hn::Max(tz0, hn::Zero(d)));
      t1 = hn::Min(hn::Min(tx1, ty1), hn::Min(tz1, hn::Set(d, t_max)));
    } else {
      t0 = hn::Max(tz0, hn::Max(ty0, hn::Max(tx0, hn::Zero(d))));
      t1 = hn::Min(tz1, hn::Min(ty1, hn::Min(tx1, hn::Set(d, t_max))));
    }
    hn::StoreU(t0, d, t_near + g);
    bits |= MaskBits(d, hn::Le(t0, t1)) << g;
  }
  return bits & OccupiedSlots(node);
}

// Lanes of a leaf group whose edge functions hit exactly 0: the scalar test decides them (in double). `block`:
// the leaf starting at triangle `first` in the run layout, runs `stride` floats apart.
template <bool kAny, class D>
HWY_NOINLINE bool RetestZeroLanesSingle(D d, hn::Mask<D> zero, const float* block, uint32_t first,
                                        uint32_t stride, size_t at, const SingleRay& r, float* t_max, Hit* hit) {
  const WatertightRay wr = r.watertight();  // built here, off the hot path
  bool found = false;
  for (uint32_t bits = MaskBits(d, zero); bits != 0; bits &= bits - 1) {
    const uint32_t i = uint32_t(at + size_t(__builtin_ctz(bits)));
    TriangleHit th;
    if (!intersect_triangle(wr, *t_max, BlockVertex(block, stride, i - first, 0),
                            BlockVertex(block, stride, i - first, 1), BlockVertex(block, stride, i - first, 2), &th))
      continue;
    if constexpr (kAny) return true;
    *t_max = th.t;
    *hit = {th.t, uint32_t(i), th.b1, th.b2};
    found = true;
  }
  return found;
}

// Leaf triangles [at, at + lanes) (leaf-order indices) against the ray, their vertices minus the ray's origin on
// its permuted axes in v[vertex][axis] (lane = triangle), lanes [live, L) past the leaf. As IntersectLeaf; lanes
// whose edge functions hit exactly 0 go to retest(zero mask).
template <bool kAny, class D, class V, class Retest>
HWY_INLINE bool TestLeafGroup(D d, const V (&v)[3][3], size_t at, uint32_t live, const SingleRay& r, float* t_max,
                              Hit* hit, const Retest& retest) {
  auto lanes = WatertightTest(d, v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2], v[2][0], v[2][1], v[2][2],
                              hn::Set(d, r.s(0)), hn::Set(d, r.s(1)), hn::Set(d, r.s(2)), hn::Set(d, *t_max),
                              hn::FirstN(d, live));
  bool found = false;
  if (!hn::AllFalse(d, lanes.hit)) ResolveHits(d, hn::Set(d, *t_max), lanes);
  if (!hn::AllFalse(d, lanes.hit)) {
    if constexpr (kAny) return true;
    // Closest lane; on equal t the first in leaf order, as a sequential scalar loop would keep.
    const auto t = hn::IfThenElse(lanes.hit, lanes.t, hn::Set(d, kInfinity));
    const auto t_min = hn::MinOfLanes(d, t);
    const size_t lane = size_t(hn::FindFirstTrue(d, hn::Eq(t, t_min)));
    *t_max = hn::GetLane(t_min);
    *hit = {*t_max, uint32_t(at + lane), hn::ExtractLane(lanes.b1, lane), hn::ExtractLane(lanes.b2, lane)};
    found = true;
  }
  if (HWY_UNLIKELY(!hn::AllFalse(d, lanes.zero)) && retest(lanes.zero)) found = true;
  return found;
}

// Leaf triangles [i, i + lanes) of the leaf (first, count), whose runs for the ray's axes start at px, py, pz
// (vertex 0; vertices 1 and 2 lie v1 and v2 floats further). As IntersectLeaf.
template <bool kAny, class D>
HWY_INLINE bool IntersectLeafGroup(D d, const float* block, uint32_t first, uint32_t count, uint32_t i,
                                   const float* px, const float* py, const float* pz, size_t v1, size_t v2,
                                   const SingleRay& r, float* t_max, Hit* hit) {
  // Broadcast here rather than once per leaf: most leaves are one group, and values kept across the loop below
  // were spilled and reloaded.
  const auto okx = hn::Set(d, r.ok(0)), oky = hn::Set(d, r.ok(1)), okz = hn::Set(d, r.ok(2));
  // Loading L lanes from any position inside a leaf's run stays within the leaf data and its kLeafPadding tail.
  const size_t at = size_t(first) + i;
  const hn::Vec<D> v[3][3] = {
      {hn::Sub(hn::LoadU(d, px + i), okx), hn::Sub(hn::LoadU(d, py + i), oky), hn::Sub(hn::LoadU(d, pz + i), okz)},
      {hn::Sub(hn::LoadU(d, px + v1 + i), okx), hn::Sub(hn::LoadU(d, py + v1 + i), oky),
       hn::Sub(hn::LoadU(d, pz + v1 + i), okz)},
      {hn::Sub(hn::LoadU(d, px + v2 + i), okx), hn::Sub(hn::LoadU(d, py + v2 + i), oky),
       hn::Sub(hn::LoadU(d, pz + v2 + i), okz)}};
  return TestLeafGroup<kAny>(d, v, at, count - i, r, t_max, hit, [&](hn::Mask<D> zero) {
    return RetestZeroLanesSingle<kAny>(d, zero, block, first, uint32_t(v1 / 3), at, r, t_max, hit);
  });
}

// Leaf groups [i, count) of a leaf, after the first, one at a time. As IntersectLeaf.
template <bool kAny, class D>
HWY_INLINE bool IntersectLeafGroupsFrom(D d, const float* block, uint32_t first, uint32_t count, uint32_t stride,
                                        uint32_t i, const float* px, const float* py, const float* pz,
                                        const SingleRay& r, float* t_max, Hit* hit) {
  const size_t v1 = 3 * size_t(stride), v2 = 6 * size_t(stride);
  bool found = false;
  for (; i < count; i += uint32_t(hn::Lanes(d))) {
    if (IntersectLeafGroup<kAny>(d, block, first, count, i, px, py, pz, v1, v2, r, t_max, hit)) {
      if constexpr (kAny) return true;
      found = true;
    }
  }
  return found;
}

// The same out of line, for targets whose first group holds 8 triangles: only leaves over 8 need more groups
// (none at the default max_leaf_size), and with the loop inline GCC saved ~8 of the first group's values to the
// stack for it at every leaf. Out of line: +3 to +6 % on diffuse rays (bunny to bunny-16m and the dragon;
// in-process A/B, medians of 7, 2026-11-23).
template <bool kAny, class D>
HWY_NOINLINE bool IntersectLeafRest(D d, const float* block, uint32_t first, uint32_t count, uint32_t stride,
                                    const float* px, const float* py, const float* pz, const SingleRay& r,
                                    float* t_max, Hit* hit) {
  return IntersectLeafGroupsFrom<kAny>(d, block, first, count, stride, uint32_t(hn::Lanes(d)), px, py, pz, r, t_max,
                                       hit);
}

// Tests leaf triangles [first, first + count) (lanes = triangles) of the leaf a child reference (less kLeafFlag)
// names (LeafFirst). Closest hit: shrinks *t_max and fills *hit with the closest hit closer than *t_max. Any hit:
// returns at the first hit. `buffer` (kLeafBufferFloats, for leaves that are decoded first: LeafBlock).
template <bool kAny, class Leaves>
HWY_INLINE bool IntersectLeaf(const Leaves& tris, uint32_t leaf, uint32_t count, const SingleRay& r,
                              float* t_max, Hit* hit, float* buffer) {
  const hn::CappedTag<float, 8> d;
  const uint32_t L = uint32_t(hn::Lanes(d));
  if constexpr (kDecodesLeaves<Leaves> && hn::MaxLanes(decltype(d)()) >= 8) {
    // Most packed leaves: decoded into registers, the run layout written only for a rare zero-edge retest.
    hn::Vec<decltype(d)> v[3][3];
    const int axis[3] = {r.k(0), r.k(1), r.k(2)};
    const float origin[3] = {r.ok(0), r.ok(1), r.ok(2)};
    if (HWY_LIKELY(PackedLeafInRegisters(d, tris, leaf, count, axis, origin, v))) {
      const uint32_t first = LeafFirst(tris, leaf);
      return TestLeafGroup<kAny>(d, v, first, count, r, t_max, hit, [&](hn::Mask<decltype(d)> zero) {
        uint32_t stride = count;
        const float* const base = LeafBlock(tris, r.leaf_data, leaf, count, buffer, &stride);
        return RetestZeroLanesSingle<kAny>(d, zero, base, first, stride, first, r, t_max, hit);
      });
    }
  }
  // Run 3 * vertex + axis of the leaf starts at base + (3 * vertex + axis) * stride (the count, or a decoded
  // leaf's vector length): the ray's permuted axes pick vertex 0's three runs, and vertices 1 and 2 lie 3 * stride
  // and 6 * stride floats further (three multiplies per leaf, and the rest fits x86 addressing modes).
  uint32_t stride = count;
  const float* const base = LeafBlock(tris, r.leaf_data, leaf, count, buffer, &stride);
  const uint32_t first = LeafFirst(tris, leaf);
  const size_t c = stride, v1 = 3 * c, v2 = 6 * c;
  const float* const px = base + size_t(r.k(0)) * c;
  const float* const py = base + size_t(r.k(1)) * c;
  const float* const pz = base + size_t(r.k(2)) * c;
  // The first group here: with 8 lanes it is the whole leaf (max_leaf_size 8 by default).
  bool found = IntersectLeafGroup<kAny>(d, base, first, count, 0, px, py, pz, v1, v2, r, t_max, hit);
  if (kAny && found) return true;
  if (HWY_LIKELY(count <= L)) return found;
  bool more;
  if constexpr (hn::MaxLanes(decltype(d)()) >= 8) {
    more = IntersectLeafRest<kAny>(d, base, first, count, stride, px, py, pz, r, t_max, hit);
  } else {
    more = IntersectLeafGroupsFrom<kAny>(d, base, first, count, stride, L, px, py, pz, r, t_max, hit);
  }
  return found || more;
}

// Software prefetch of a node (all its cache lines) or of a leaf (PrefetchLeaf; leaf_data: TriangleLeaves::data).
// Also used by the packet kernel.
template <class Tree, class Leaves>
HWY_INLINE void Prefetch(const Tree& bvh, const Leaves& tris, const float* leaf_data, uint32_t ref, uint32_t count) {
  using Node = typename Tree::Node;
  if (!(ref & kLeafFlag)) {
    // A node is whole, aligned cache lines: no loop.
    const char* p = reinterpret_cast<const char*>(&bvh.nodes[ref]);
    static_assert(sizeof(Node) % 64 == 0 && alignof(Node) == 64);
    for (size_t line = 0; line < sizeof(Node); line += 64) __builtin_prefetch(p + line);
    return;
  }
  PrefetchLeaf(tris, leaf_data, ref & ~kLeafFlag, count);
}

// Closest hit (kAny = false: fills *hit, returns whether anything was hit) or any hit (returns occlusion), in the
// subtree (ref, count): the whole tree by default (the root is node 0), or a packet entry's subtree when a packet
// kernel hands its few remaining rays over to single-ray traversal.
// kCount: adds the nodes visited and the triangles tested to *cost (the traversal_cost AOV; a separate
// instantiation, so the renderer's kernels carry no counters).
template <bool kAny, bool kFma, bool kCount = false, class Tree, class Leaves>
HWY_INLINE bool TraceRayWith(const Tree& bvh, const Leaves& tris, const SingleRay& r, float t_max,
                             Hit* hit, uint32_t ref = 0, uint32_t count = 0, TraversalCost* cost = nullptr) {
  constexpr int N = Tree::kWidth;
  using Node = typename Tree::Node;
  struct Entry {
    uint32_t ref, count;
    float t_near;
  };
  // Each level above leaves at most N - 1 entries; the deepest node (level kMaxWideDepth) briefly holds all N of
  // its children while sorting them: (kMaxWideDepth - 1) (N - 1) + N entries, exactly the size below.
  Entry stack[kMaxWideDepth * (N - 1) + 1];
  int sp = 0;
  bool found = false;
  const Node* const nodes = bvh.nodes.data();  // held here: stores through hit may alias bvh.nodes
  // Decoded leaves (LeafBlock) only: the default layout's kernel keeps no buffer.
  alignas(kDecodesLeaves<Leaves> ? 64 : 4) float buffer[kDecodesLeaves<Leaves> ? kLeafBufferFloats : 1];
  for (;;) {
    if (ref & kLeafFlag) {
      if constexpr (kCount) cost->prims += count;
      if (IntersectLeaf<kAny>(tris, ref & ~kLeafFlag, count, r, &t_max, hit, buffer)) {
        if constexpr (kAny) return true;
        found = true;
      }
    } else {
      const Node& node = nodes[ref];
      if constexpr (kCount) ++cost->nodes;
      // The child references (the node's last line) are read right after the slab test, which loads only the
      // plane lines: start loading them alongside, or each node costs two memory latencies in a row on trees
      // beyond the caches (+1 % on the bunny, +3.6 % on bunny-4m, +5 to 7 % on bunny-16m; AVX3, 2026-11-23).
      __builtin_prefetch(node.child);
      alignas(64) float t_near[N];
      uint32_t bits = IntersectChildren<N, kFma>(node, r, t_max, t_near);
      if (bits != 0) {
        const uint32_t first = uint32_t(__builtin_ctz(bits));
        bits &= bits - 1;
        if (bits == 0) {  // one child: no ordering, no push
          ref = node.child[first];
          count = node.leaf_count[first];
          continue;
        }
        if constexpr (kAny) {
          // Any hit ends the search: no ordering.
          for (; bits != 0; bits &= bits - 1) {
            const uint32_t c = uint32_t(__builtin_ctz(bits));
            stack[sp++] = {node.child[c], node.leaf_count[c], 0.0f};
          }
          ref = node.child[first];
          count = node.leaf_count[first];
          continue;
        } else {
          const uint32_t second = uint32_t(__builtin_ctz(bits));
          bits &= bits - 1;
          if (bits == 0) {
            // Two children, the commonest case after one: visit the nearer (the second on a tie, as the sort
            // below would), push the other.
            const bool second_nearer = !(t_near[first] < t_near[second]);
            const uint32_t near = second_nearer ? second : first, far = second_nearer ? first : second;
            stack[sp++] = {node.child[far], node.leaf_count[far], t_near[far]};
            ref = node.child[near];
            count = node.leaf_count[near];
            Prefetch(bvh, tris, r.leaf_data, stack[sp - 1].ref, stack[sp - 1].count);
            continue;
          }
          bits |= 1u << second;
          // Insertion sort of the hit children straight onto the stack, far to near (at most N = 8 of them,
          // usually 3); the nearest ends on top and is visited next. Against sorting slot numbers first and
          // pushing them in a second loop (which GCC unrolled, with many values saved to the stack): +0.9 to
          // +1.7 % on diffuse rays (in-process A/B, five scenes, 2026-11-23).
          const int base = sp;
          for (bits |= 1u << first; bits != 0; bits &= bits - 1) {
            const uint32_t c = uint32_t(__builtin_ctz(bits));
            const Entry e{node.child[c], node.leaf_count[c], t_near[c]};
            int j = sp++;
            for (; j > base && stack[j - 1].t_near < e.t_near; --j) stack[j] = stack[j - 1];
            stack[j] = e;
          }
          --sp;
          ref = stack[sp].ref;
          count = stack[sp].count;
          // The second nearest child is the likeliest next pop: start loading it (prefetching every pushed child
          // measured no better).
          Prefetch(bvh, tris, r.leaf_data, stack[sp - 1].ref, stack[sp - 1].count);
          continue;
        }
      }
    }
    // Pop the next entry that can still hold a closer hit.
    for (;;) {
      if (sp == 0) return found;
      const Entry& e = stack[--sp];
      if (kAny || e.t_near <= t_max) {
        ref = e.ref;
        count = e.count;
        break;
      }
    }
  }
}

// TraceRayWith with the ray's slab test: the FMA test unless a direction component is zero or tiny.
template <bool kAny, bool kCount = false, class Tree, class Leaves>
HWY_INLINE bool TraceRay(const Tree& bvh, const Leaves& tris, const SingleRay& r, float t_max,
                         Hit* hit, uint32_t ref = 0, uint32_t count = 0, TraversalCost* cost = nullptr) {
  if (HWY_LIKELY(r.fma_slabs())) return TraceRayWith<kAny, true, kCount>(bvh, tris, r, t_max, hit, ref, count, cost);
  return TraceRayWith<kAny, false, kCount>(bvh, tris, r, t_max, hit, ref, count, cost);
}

// Rays a block at a time: the per-ray constants for the whole block with vector ops (single_ray-inl.h), then
// each ray's traversal.
// costs (ClosestSingleCounted): per ray, the work its search did is added to costs[i].
template <class Tree, class Leaves, bool kCount = false>
void ClosestSingle(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits,
                   TraversalCost* costs = nullptr) {
  constexpr int N = Tree::kWidth;
  RayBlock block;
  float extent[3];
  TreeExtent(bvh, extent);
  for (size_t first = 0; first < count; first += kRayBlock) {
    const size_t n = std::min(kRayBlock, count - first);
    SetupRays<N>(rays, first, n, extent, block);
    traverse_detail::prefetch_rays(rays, first + traverse_detail::kRayPrefetchAhead, count);
    for (size_t j = 0; j < n; ++j) {
      Hit& hit = hits[first + j];
      hit = Hit{};
      if (bvh.nodes.empty() || ((block.valid >> j) & 1) == 0) continue;
      TraceRay<false, kCount>(bvh, tris, SingleRay{&block, j, LeafData(tris)}, block.t_max[j], &hit, 0, 0,
                              kCount ? &costs[first + j] : nullptr);
    }
  }
}

template <class Tree, class Leaves>
void ClosestSingleCounted(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits,
                          TraversalCost* costs) {
  ClosestSingle<Tree, Leaves, true>(bvh, tris, rays, count, hits, costs);
}

template <class Tree, class Leaves>
void AnySingle(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, uint8_t* occluded) {
  constexpr int N = Tree::kWidth;
  RayBlock block;
  float extent[3];
  TreeExtent(bvh, extent);
  for (size_t first = 0; first < count; first += kRayBlock) {
    const size_t n = std::min(kRayBlock, count - first);
    SetupRays<N>(rays, first, n, extent, block);
    traverse_detail::prefetch_rays(rays, first + traverse_detail::kRayPrefetchAhead, count);
    for (size_t j = 0; j < n; ++j) {
      const bool traced = !bvh.nodes.empty() && ((block.valid >> j) & 1) != 0;
      occluded[first + j] =
          traced && TraceRay<true>(bvh, tris, SingleRay{&block, j, LeafData(tris)}, block.t_max[j], nullptr);
    }
  }
}

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_TRAVERSE_SINGLE_INL_H_TARGET
