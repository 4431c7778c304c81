// The node and leaf tests of the packet traversal kernels (traverse_packet.cc; the algorithm is described there):
// interval culling of a same-octant packet against a node's children and a leaf's triangles, the per-lane slab
// test of a node's children, and the per-lane watertight test of a leaf's triangles. Include after packet-inl.h
// (per-target part) inside a foreach_target file compiled without FMA contraction.

// Per-target include guard (Highway's pattern).
#if defined(TORTE_SIMD_PACKET_TESTS_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_PACKET_TESTS_INL_H_TARGET
#undef TORTE_SIMD_PACKET_TESTS_INL_H_TARGET
#else
#define TORTE_SIMD_PACKET_TESTS_INL_H_TARGET
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

#include "accel/wide_bvh.h"
#include "geometry/triangle.h"
#include "layout-inl.h"
#include "packet-inl.h"
#include "traverse-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

using traverse_detail::bound_offset;
using traverse_detail::kFarRound;

// The interval slab test of one axis k of a same-octant packet (interval_axes bit k set) against planes n (entry)
// and f (exit), lanes = boxes, for origins in [o_lo, o_hi]: raises t0 to a lower bound of every ray's entry
// distance and lowers t1 to an upper bound of every exit distance. A ray's slab distance is fl(fl(b - o) * inv),
// monotonic in o and in inv as each rounding is: with inv > 0 it is smallest at o = o_hi and largest at o = o_lo,
// with inv < 0 the other way round, and for a fixed b - o it is extreme at inv = i_lo or i_hi. So two products per
// plane bound all rays (a full interval product takes four).
template <size_t P, class D, class V = hn::Vec<D>>
HWY_INLINE void IntervalSlab(D d, const Packet<P>& p, int k, float o_lo, float o_hi, V n, V f, V& t0, V& t1) {
  const bool neg = p.i_hi[k] < 0;  // same octant: every lane's inverse direction has this sign
  const auto ilo = hn::Set(d, p.i_lo[k]), ihi = hn::Set(d, p.i_hi[k]);
  const auto dn = hn::Sub(n, hn::Set(d, neg ? o_lo : o_hi));
  const auto df = hn::Sub(f, hn::Set(d, neg ? o_hi : o_lo));
  const auto near_lo = hn::Min(hn::Mul(dn, ilo), hn::Mul(dn, ihi));
  const auto far_hi = hn::Mul(hn::Max(hn::Mul(df, ilo), hn::Mul(df, ihi)), hn::Set(d, kFarRound));
  t0 = hn::Max(t0, near_lo), t1 = hn::Min(t1, far_hi);
}

// Children of a node (its planes `nf`: NodePlanes) that some valid ray of a same-octant packet may hit:
// IntervalSlab on every interval axis (Reshetov et al. 2005). A child rejected here fails every lane's own test.
// t_lo (optional) gets each child's lower bound of the entry distance.
template <int N, size_t P>
HWY_INLINE uint32_t IntervalChildren(const float* nf, const Packet<P>& p, float* t_lo = nullptr) {
  const hn::CappedTag<float, N> d;
  const size_t L = hn::Lanes(d);
  uint32_t bits = 0;
  for (size_t g = 0; g < size_t(N); g += L) {
    auto t0 = hn::Zero(d), t1 = hn::Set(d, p.t_hi);
    for (int k = 0; k < 3; ++k) {
      if (!((p.interval_axes >> k) & 1)) continue;
      IntervalSlab(d, p, k, p.o_lo[k], p.o_hi[k], hn::Load(d, nf + p.near_off[k] + g),
                   hn::Load(d, nf + p.far_off[k] + g), t0, t1);
    }
    if (t_lo) hn::StoreU(t0, d, t_lo + g);
    bits |= MaskBits(d, hn::Le(t0, t1)) << g;
  }
  return bits;
}

// Triangles [g, g + 8) of the leaf (base, count; runs `stride` floats apart, traverse_single-inl.h) whose bounds the
// packet's interval may hit, as bits (lanes = triangles): IntervalSlab on each triangle's bounds, for origins
// widened by a margin on both sides (p.tri_o_lo, p.tri_o_hi; the same as widening the bounds), so that no
// triangle the watertight test would hit for a lane is skipped. That test is exact for vertices sheared in float,
// which lie within a few float roundings of the true ones (relative to the coordinates and the origin); the margin
// is 2^-20 of the scene's extent plus the origin, twice what that takes, and the far bound t_hi is raised by
// 2^-18 for the rounding of t.
template <size_t P>
HWY_INLINE uint32_t IntervalTriangles(const float* base, size_t count, size_t stride, size_t g,
                                      const Packet<P>& p) {
  const hn::CappedTag<float, 8> d;
  const size_t L = hn::Lanes(d);  // 8, or fewer on narrow targets: lane groups
  const auto t_hi = hn::Set(d, p.t_hi * (1.0f + 0x1p-18f));
  uint32_t bits = 0;
  for (size_t h = g; h < g + 8 && h < count; h += L) {
    auto t0 = hn::Zero(d), t1 = t_hi;
    for (int k = 0; k < 3; ++k) {
      if (!((p.interval_axes >> k) & 1)) continue;
      const float* r = base + size_t(k) * stride + h;  // vertex 0 on axis k; vertices 1 and 2 are 3 and 6 runs on
      const auto a = hn::LoadU(d, r), b = hn::LoadU(d, r + 3 * stride), c = hn::LoadU(d, r + 6 * stride);
      const auto lo = hn::Min(a, hn::Min(b, c)), hi = hn::Max(a, hn::Max(b, c));
      const bool neg = p.i_hi[k] < 0;
      IntervalSlab(d, p, k, p.tri_o_lo[k], p.tri_o_hi[k], neg ? hi : lo, neg ? lo : hi, t0, t1);
    }
    bits |= MaskBits(d, hn::And(hn::Le(t0, t1), hn::FirstN(d, count - h))) << (h - g);
  }
  return bits;
}

// child_lanes[0, N) = lanes.
template <int N>
HWY_INLINE void FillLanes(uint32_t* child_lanes, uint32_t lanes) {
  const hn::CappedTag<uint32_t, N> du;
  for (size_t g = 0; g < size_t(N); g += hn::Lanes(du)) hn::StoreU(hn::Set(du, lanes), du, child_lanes + g);
}

// Occupied child slots, and leaf children, as bits (of a WideNode<N> or a QuantNode).
template <int N, class Node>
HWY_INLINE uint32_t NonEmptyChildren(const Node& node) {
  // A vector compare: the scalar loop over the N children cost ~65 instructions per node visit (callgrind).
  const hn::CappedTag<uint32_t, N> du;
  uint32_t bits = 0;
  for (size_t g = 0; g < size_t(N); g += hn::Lanes(du))
    bits |= MaskBits(du, hn::Ne(hn::LoadU(du, node.child + g), hn::Set(du, kEmptyChild))) << g;
  return bits;
}
template <int N, class Node>
HWY_INLINE uint32_t LeafChildren(const Node& node) {
  const hn::CappedTag<uint8_t, N> d8;
  uint32_t bits = 0;
  for (size_t g = 0; g < size_t(N); g += hn::Lanes(d8))
    bits |= MaskBits(d8, hn::Ne(hn::LoadU(d8, node.leaf_count + g), hn::Zero(d8))) << g;
  return bits;
}

// Slab test of the N children of `node` (its planes `nf`: NodePlanes) against the packet's rays in `lanes`.
// Returns the hit children as bits; child_lanes[c] gets the lanes hitting child c and, with kNear, t_near[c] the
// smallest entry distance among them.
template <bool kNear, int N, size_t P, class Node>
HWY_INLINE uint32_t PacketChildren(const Node& node, const float* nf, const Packet<P>& p, uint32_t lanes,
                                   uint32_t cand, uint32_t* child_lanes, float* t_near) {
  const hn::CappedTag<float, P> d;
  const size_t L = hn::Lanes(d);
  const auto round = hn::Set(d, kFarRound);
  const auto inf = hn::Set(d, kInfinity);
  // Only the candidate slots, as bits: a loop over all N slots testing each cost ~16 instructions per ray.
  const uint32_t todo = cand & NonEmptyChildren<N>(node);
  for (uint32_t b = todo; b != 0; b &= b - 1) {
    child_lanes[__builtin_ctz(b)] = 0;
    if constexpr (kNear) t_near[__builtin_ctz(b)] = kInfinity;
  }
  uint32_t hit_children = 0;
  for (size_t g = 0; g < P; g += L) {
    const uint32_t group_lanes = (lanes >> g) & GroupMask(d);
    if (group_lanes == 0) continue;
    const auto ox = hn::Load(d, p.ox + g), oy = hn::Load(d, p.oy + g), oz = hn::Load(d, p.oz + g);
    const auto ix = hn::Load(d, p.ix + g), iy = hn::Load(d, p.iy + g), iz = hn::Load(d, p.iz + g);
    const auto t_max = hn::Load(d, p.t_max + g);
    const auto neg_x = hn::MaskFromVec(hn::Load(d, p.neg[0] + g));
    const auto neg_y = hn::MaskFromVec(hn::Load(d, p.neg[1] + g));
    const auto neg_z = hn::MaskFromVec(hn::Load(d, p.neg[2] + g));
    for (uint32_t b = todo; b != 0; b &= b - 1) {
      const int c = __builtin_ctz(b);
      hn::Vec<decltype(d)> nx, ny, nz, fx, fy, fz;
      if (p.same_octant) {  // near/far planes picked once for the packet
        nx = hn::Set(d, nf[p.near_off[0] + c]), ny = hn::Set(d, nf[p.near_off[1] + c]);
        nz = hn::Set(d, nf[p.near_off[2] + c]), fx = hn::Set(d, nf[p.far_off[0] + c]);
        fy = hn::Set(d, nf[p.far_off[1] + c]), fz = hn::Set(d, nf[p.far_off[2] + c]);
      } else {  // per lane
        const auto plane = [&](int a, bool hi) { return hn::Set(d, nf[bound_offset<N>(a, hi) + c]); };
        const auto lx = plane(0, false), ly = plane(1, false), lz = plane(2, false);
        const auto hx = plane(0, true), hy = plane(1, true), hz = plane(2, true);
        nx = hn::IfThenElse(neg_x, hx, lx), fx = hn::IfThenElse(neg_x, lx, hx);
        ny = hn::IfThenElse(neg_y, hy, ly), fy = hn::IfThenElse(neg_y, ly, hy);
        nz = hn::IfThenElse(neg_z, hz, lz), fz = hn::IfThenElse(neg_z, lz, hz);
      }
      // Same arithmetic as the single-ray test (and SlabRay), NaN slabs ignored by keeping the accumulator second.
      const auto tx0 = hn::Mul(hn::Sub(nx, ox), ix), ty0 = hn::Mul(hn::Sub(ny, oy), iy);
      const auto tz0 = hn::Mul(hn::Sub(nz, oz), iz);
      const auto tx1 = hn::Mul(hn::Mul(hn::Sub(fx, ox), ix), round);
      const auto ty1 = hn::Mul(hn::Mul(hn::Sub(fy, oy), iy), round);
      const auto tz1 = hn::Mul(hn::Mul(hn::Sub(fz, oz), iz), round);
      const auto t0 = hn::Max(tz0, hn::Max(ty0, hn::Max(tx0, hn::Zero(d))));
      const auto t1 = hn::Min(tz1, hn::Min(ty1, hn::Min(tx1, t_max)));
      const auto hit = hn::Le(t0, t1);
      // A ray that missed the parent misses the child too (child boxes lie inside, rounding is monotonic);
      // masking keeps the lane sets exact anyway.
      const uint32_t bits = MaskBits(d, hit) & group_lanes;
      if (bits == 0) continue;
      child_lanes[c] |= bits << g;
      hit_children |= 1u << c;
      if constexpr (kNear) {
        const float t = hn::GetLane(hn::MinOfLanes(d, hn::IfThenElse(hit, t0, inf)));
        t_near[c] = t < t_near[c] ? t : t_near[c];
      }
    }
  }
  return hit_children;
}

// Lanes whose edge functions hit exactly 0 against triangle i: decided by the scalar test (in double). `block`:
// the leaf starting at triangle `first` in the run layout, runs `stride` floats apart.
template <bool kAny, size_t P, class D>
HWY_NOINLINE void RetestZeroLanes(D d, hn::Mask<D> zero, size_t g, const float* block, uint32_t first,
                                  uint32_t stride, uint32_t i, Packet<P>& p) {
  const Vec3f p0 = BlockVertex(block, stride, i - first, 0), p1 = BlockVertex(block, stride, i - first, 1),
              p2 = BlockVertex(block, stride, i - first, 2);
  for (uint32_t bits = MaskBits(d, zero); bits != 0; bits &= bits - 1) {
    const size_t lane = g + size_t(__builtin_ctz(bits));
    TriangleHit th;
    if (!intersect_triangle(WatertightRay(p.ray(lane)), p.t_max[lane], p0, p1, p2, &th)) continue;
    if constexpr (kAny) {
      p.t_max[lane] = -kInfinity;
    } else {
      p.t_max[lane] = th.t;
      p.prim[lane] = i;
      p.b1[lane] = th.b1;
      p.b2[lane] = th.b2;
    }
  }
}

// Picks per lane the coordinate of axis k of the lane's permutation: x, y or z.
template <class D, size_t P, class V = hn::Vec<D>>
HWY_INLINE V PermutedCoord(D d, const Packet<P>& p, int k, size_t g, float x, float y, float z) {
  const auto is0 = hn::MaskFromVec(hn::Load(d, p.axis_is[k][0] + g));
  const auto is1 = hn::MaskFromVec(hn::Load(d, p.axis_is[k][1] + g));
  return hn::IfThenElse(is0, hn::Set(d, x), hn::IfThenElse(is1, hn::Set(d, y), hn::Set(d, z)));
}

// Tests leaf triangle i (leaf-order index; at = i - first) of the leaf starting at `first`, in the run layout at
// `base` (runs `stride` floats apart), against the packet's lanes (lanes = rays). `run`: when the packet has one axis permutation, the leaf's
// runs per vertex and permuted axis. Closest hit: lanes keep the closest hit (t_max shrinks). Any hit: hit lanes
// are retired (t_max = -inf). Returns false when no lane can have been hit.
template <bool kAny, size_t P>
HWY_INLINE bool PacketTriangle(const float* base, uint32_t first, uint32_t stride, uint32_t at,
                               const float* const (&run)[3][3], uint32_t lanes, Packet<P>& p) {
  const hn::CappedTag<float, P> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  const size_t L = hn::Lanes(d);
  const auto zero = hn::Zero(d);
  const uint32_t i = first + at;
  bool found = false;
  for (size_t g = 0; g < P; g += L) {
    if (((lanes >> g) & GroupMask(d)) == 0) continue;
    const auto t_max = hn::Load(d, p.t_max + g);
    const auto okx = hn::Load(d, p.okx + g), oky = hn::Load(d, p.oky + g), okz = hn::Load(d, p.okz + g);
    // Vertex minus origin on the lane's permuted axes: the values the scalar test computes, so the same
    // decisions follow. Mixed permutations select per lane.
    hn::Vec<decltype(d)> a[3][3];
    for (int k = 0; k < 3; ++k) {
      if (p.same_axes) {
        a[k][0] = hn::Sub(hn::Set(d, run[k][0][at]), okx);
        a[k][1] = hn::Sub(hn::Set(d, run[k][1][at]), oky);
        a[k][2] = hn::Sub(hn::Set(d, run[k][2][at]), okz);
      } else {
        const float* const t = base + at;
        const float x = t[size_t(3 * k) * stride], y = t[size_t(3 * k + 1) * stride];
        const float z = t[size_t(3 * k + 2) * stride];
        a[k][0] = hn::Sub(PermutedCoord(d, p, 0, g, x, y, z), okx);
        a[k][1] = hn::Sub(PermutedCoord(d, p, 1, g, x, y, z), oky);
        a[k][2] = hn::Sub(PermutedCoord(d, p, 2, g, x, y, z), okz);
      }
    }
    // Any hit skips the rest when no lane is inside and branches on hits; closest hit runs branch-free to the
    // end: after the interval test, whether a lane is inside is a coin toss (half of the tests), which the
    // branches mispredicted (branch-free: +1.5 to 5 % on camera packets, AVX3, 2026-11-23).
    auto r = WatertightTest<kAny>(d, a[0][0], a[0][1], a[0][2], a[1][0], a[1][1], a[1][2], a[2][0], a[2][1],
                                  a[2][2], hn::Load(d, p.sx + g), hn::Load(d, p.sy + g), hn::Load(d, p.sz + g),
                                  t_max, hn::Gt(t_max, zero));  // live lanes have t_max > 0
    if constexpr (kAny) {
      if (!hn::AllFalse(d, r.hit)) ResolveHits(d, t_max, r);
      if (!hn::AllFalse(d, r.hit)) {
        found = true;
        hn::Store(hn::IfThenElse(r.hit, hn::Set(d, -kInfinity), t_max), d, p.t_max + g);
      }
    } else {
      ResolveHits(d, t_max, r);  // lanes not hit may divide by 0: their results are discarded
      found |= !hn::AllFalse(d, r.hit);
      hn::Store(hn::IfThenElse(r.hit, r.t, t_max), d, p.t_max + g);
      hn::Store(hn::IfThenElse(r.hit, r.b1, hn::Load(d, p.b1 + g)), d, p.b1 + g);
      hn::Store(hn::IfThenElse(r.hit, r.b2, hn::Load(d, p.b2 + g)), d, p.b2 + g);
      const auto prim = hn::Load(du, p.prim + g);
      hn::Store(hn::IfThenElse(hn::RebindMask(du, r.hit), hn::Set(du, i), prim), du, p.prim + g);
    }
    if (HWY_UNLIKELY(!hn::AllFalse(d, r.zero))) {
      RetestZeroLanes<kAny>(d, r.zero, g, base, first, stride, i, p);
      found = true;  // maybe a hit: the caller re-checks the lanes
    }
  }
  return found;
}

// Tests leaf triangles [first, first + count) of the leaf `leaf` names (LeafFirst) against the packet's lanes, one
// triangle at a time (PacketTriangle). Closest-hit packets of one octant first drop the triangles their interval
// misses (IntervalTriangles: on camera packets three quarters of a leaf's triangles, which no lane would have
// hit). Returns false when no lane can have been hit (the any-hit caller then skips its all-occluded check).
// Gathered or decoded leaves (LeafBlock) are put in the run layout once into `buffer` (kLeafBufferFloats) for all
// lanes.
template <bool kAny, size_t P, class Leaves>
HWY_INLINE bool PacketLeaf(const Leaves& tris, uint32_t leaf, uint32_t count, uint32_t lanes, Packet<P>& p,
                           float* buffer) {
  uint32_t stride = count;
  const float* const base = LeafBlock(tris, LeafData(tris), leaf, count, buffer, &stride);
  const uint32_t first = LeafFirst(tris, leaf);
  // One permutation for the packet (camera and shadow packets): vertex k's coordinate on permuted axis j is run
  // 3 k + axes[j] of the leaf, broadcast straight from the leaf (staging the nine floats per triangle on the stack
  // cost ~40 instructions per triangle, callgrind).
  const float* run[3][3] = {};  // set when same_axes (initialised: GCC cannot see that)
  if (p.same_axes)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) run[k][j] = base + size_t(3 * k + p.axes[j]) * stride;
  bool found = false;
  if (!kAny && p.same_octant) {
    for (uint32_t g = 0; g < count; g += 8)
      for (uint32_t bits = IntervalTriangles(base, count, stride, g, p); bits != 0; bits &= bits - 1)
        found |= PacketTriangle<kAny>(base, first, stride, g + uint32_t(__builtin_ctz(bits)), run, lanes, p);
  } else {
    for (uint32_t at = 0; at < count; ++at) found |= PacketTriangle<kAny>(base, first, stride, at, run, lanes, p);
  }
  return found;
}

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_PACKET_TESTS_INL_H_TARGET
