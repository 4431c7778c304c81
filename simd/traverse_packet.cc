// Packet traversal of WideBvh<N> + TriangleLeaves: P = 8 or 16 consecutive rays per packet, lanes = rays
// (CappedTag<float, P>; narrower targets loop over lane groups). See traverse.h for the semantics; the packet
// itself (per-lane state, set-up, lane queries) is in packet-inl.h.
// Nodes: each child box is tested against all rays of the packet that reached the node; a child is skipped when
// none of them hits it, and hit children are visited in order of the smallest entry distance among their rays.
// Each stack entry carries the lanes that hit its box, so lane groups without such rays are skipped below it.
// Leaves: one triangle at a time against all lanes, with the watertight test of traverse-inl.h.
// In a same-octant packet the node's children are first tested against the packet's interval of origins / inverse
// directions (one vector test for all N children, Reshetov et al. 2005); the interval's far bound is the largest
// t_max of the packet, which closest hit lowers as its lanes find hits. Closest hit then takes the interval's
// verdict for interior children (they inherit the node's lanes and are ordered by the interval's entry bound) and
// tests only leaf children lane by lane, unless the packet's rays have parted (per-lane mode, see PacketStats);
// any hit tests the survivors lane by lane (it needs live-lane counts for the single-ray fallback). Closest-hit
// leaves of such packets test the interval against each triangle's bounds first (8 triangles per vector) and
// skip the triangles it misses: three quarters of them for camera packets. The any-hit leaf test skips the
// division when no lane is inside the triangle; closest hit, where that is a coin toss after the culling, runs
// branch-free.
// Any hit, and closest hit in per-lane mode: once an entry holds few live rays (kSingleThreshold,
// kClosestSingleThreshold) its subtree is traced one ray at a time with the single-ray kernel (Benthin et al.
// 2012). Any hit visits children in any order (no entry distances computed).
// Rays that are done (invalid input, padding past `count`, occluded in an any-hit query) get t_max = -inf, which
// fails every slab and triangle test, so they never disturb the others; an any-hit packet stops when all its
// rays are occluded.

// No FMA contraction (see traverse.cc): the watertight test must round exactly like the scalar one.
#include "core/no_fp_contract.h"  // before every other include

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "accel/bvh_build.h"
#include "core/error.h"
#include "geometry/triangle.h"
#include "traverse.h"

#include <hwy/cache_control.h>  // Stream, FlushStream

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "traverse_packet.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>                  // IWYU pragma: keep
#include <hwy/highway.h>

#include "traverse-inl.h"
#include "packet-inl.h"
#include "traverse_single-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

using traverse_detail::kFarRound;
using traverse_detail::kMaxWideDepth;
using traverse_detail::node_floats;

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

// Children of `node` that some valid ray of a same-octant packet may hit: IntervalSlab on every interval axis
// (Reshetov et al. 2005). A child rejected here fails every lane's own test. t_lo (optional) gets each child's
// lower bound of the entry distance.
template <int N, size_t P>
HWY_INLINE uint32_t IntervalChildren(const WideNode<N>& node, const Packet<P>& p, float* t_lo = nullptr) {
  const hn::CappedTag<float, N> d;
  const size_t L = hn::Lanes(d);
  const float* nf = node_floats(node);
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

// Triangles [g, g + 8) of the leaf (base, count) (leaf-order runs, traverse_single-inl.h) whose bounds the
// packet's interval may hit, as bits (lanes = triangles): IntervalSlab on each triangle's bounds, for origins
// widened by a margin on both sides (p.tri_o_lo, p.tri_o_hi; the same as widening the bounds), so that no
// triangle the watertight test would hit for a lane is skipped. That test is exact for vertices sheared in float,
// which lie within a few float roundings of the true ones (relative to the coordinates and the origin); the margin
// is 2^-20 of the scene's extent plus the origin, twice what that takes, and the far bound t_hi is raised by
// 2^-18 for the rounding of t.
template <size_t P>
HWY_INLINE uint32_t IntervalTriangles(const float* base, size_t count, size_t g, const Packet<P>& p) {
  const hn::CappedTag<float, 8> d;
  const size_t L = hn::Lanes(d);  // 8, or fewer on narrow targets: lane groups
  const auto t_hi = hn::Set(d, p.t_hi * (1.0f + 0x1p-18f));
  uint32_t bits = 0;
  for (size_t h = g; h < g + 8 && h < count; h += L) {
    auto t0 = hn::Zero(d), t1 = t_hi;
    for (int k = 0; k < 3; ++k) {
      if (!((p.interval_axes >> k) & 1)) continue;
      const float* r = base + size_t(k) * count + h;  // vertex 0 on axis k; vertices 1 and 2 are 3 and 6 runs on
      const auto a = hn::LoadU(d, r), b = hn::LoadU(d, r + 3 * count), c = hn::LoadU(d, r + 6 * count);
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

// Occupied child slots, and leaf children, as bits.
template <int N>
HWY_INLINE uint32_t NonEmptyChildren(const WideNode<N>& node) {
  // A vector compare: the scalar loop over the N children cost ~65 instructions per node visit (callgrind).
  const hn::CappedTag<uint32_t, N> du;
  uint32_t bits = 0;
  for (size_t g = 0; g < size_t(N); g += hn::Lanes(du))
    bits |= MaskBits(du, hn::Ne(hn::LoadU(du, node.child + g), hn::Set(du, kEmptyChild))) << g;
  return bits;
}
template <int N>
HWY_INLINE uint32_t LeafChildren(const WideNode<N>& node) {
  const hn::CappedTag<uint8_t, N> d8;
  uint32_t bits = 0;
  for (size_t g = 0; g < size_t(N); g += hn::Lanes(d8))
    bits |= MaskBits(d8, hn::Ne(hn::LoadU(d8, node.leaf_count + g), hn::Zero(d8))) << g;
  return bits;
}

// Slab test of the N children of `node` against the packet's rays in `lanes`. Returns the hit children as bits;
// child_lanes[c] gets the lanes hitting child c and, with kNear, t_near[c] the smallest entry distance among them.
template <bool kNear, int N, size_t P>
HWY_INLINE uint32_t PacketChildren(const WideNode<N>& node, const Packet<P>& p, uint32_t lanes, uint32_t cand,
                                   uint32_t* child_lanes, float* t_near) {
  const hn::CappedTag<float, P> d;
  const size_t L = hn::Lanes(d);
  const float* nf = node_floats(node);
  const auto round = hn::Set(d, kFarRound);
  const auto inf = hn::Set(d, kInfinity);
  // Only the candidate slots, as bits: a loop over all N slots testing each cost ~16 instructions per ray.
  const uint32_t todo = cand & NonEmptyChildren(node);
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
        const auto lx = hn::Set(d, node.lo_x[c]), ly = hn::Set(d, node.lo_y[c]), lz = hn::Set(d, node.lo_z[c]);
        const auto hx = hn::Set(d, node.hi_x[c]), hy = hn::Set(d, node.hi_y[c]), hz = hn::Set(d, node.hi_z[c]);
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

// Lanes whose edge functions hit exactly 0 against triangle i: decided by the scalar test (in double).
template <bool kAny, size_t P, class D>
HWY_NOINLINE void RetestZeroLanes(D d, hn::Mask<D> zero, size_t g, const TriangleLeaves& tris, uint32_t first,
                                  uint32_t count, uint32_t i, Packet<P>& p) {
  const Vec3f p0 = tris.vertex(first, count, i, 0), p1 = tris.vertex(first, count, i, 1),
              p2 = tris.vertex(first, count, i, 2);
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

// Tests leaf triangle i (leaf-order index; at = i - first) of the leaf (first, count) against the packet's lanes
// (lanes = rays). `run`: when the packet has one axis permutation, the leaf's runs per vertex and permuted axis.
// Closest hit: lanes keep the closest hit (t_max shrinks). Any hit: hit lanes are retired (t_max = -inf).
// Returns false when no lane can have been hit.
template <bool kAny, size_t P>
HWY_INLINE bool PacketTriangle(const TriangleLeaves& tris, uint32_t first, uint32_t count, uint32_t at,
                               const float* const (&run)[3][3], uint32_t lanes, Packet<P>& p) {
  const hn::CappedTag<float, P> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  const size_t L = hn::Lanes(d);
  const auto zero = hn::Zero(d);
  const float* const base = tris.data.data() + 9 * size_t(first);
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
        const float x = t[size_t(3 * k) * count], y = t[size_t(3 * k + 1) * count];
        const float z = t[size_t(3 * k + 2) * count];
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
      RetestZeroLanes<kAny>(d, r.zero, g, tris, first, count, i, p);
      found = true;  // maybe a hit: the caller re-checks the lanes
    }
  }
  return found;
}

// Tests leaf triangles [first, first + count) against the packet's lanes, one triangle at a time (PacketTriangle).
// Closest-hit packets of one octant first drop the triangles their interval misses (IntervalTriangles: on camera
// packets three quarters of a leaf's triangles, which no lane would have hit). Returns false when no lane can have
// been hit (the any-hit caller then skips its all-occluded check).
template <bool kAny, size_t P>
HWY_INLINE bool PacketLeaf(const TriangleLeaves& tris, uint32_t first, uint32_t count, uint32_t lanes, Packet<P>& p) {
  const float* const base = tris.data.data() + 9 * size_t(first);
  // One permutation for the packet (camera and shadow packets): vertex k's coordinate on permuted axis j is run
  // 3 k + axes[j] of the leaf, broadcast straight from the leaf (staging the nine floats per triangle on the stack
  // cost ~40 instructions per triangle, callgrind).
  const float* run[3][3] = {};  // set when same_axes (initialised: GCC cannot see that)
  if (p.same_axes)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) run[k][j] = base + size_t(3 * k + p.axes[j]) * count;
  bool found = false;
  if (!kAny && p.same_octant) {
    for (uint32_t g = 0; g < count; g += 8)
      for (uint32_t bits = IntervalTriangles(base, count, g, p); bits != 0; bits &= bits - 1)
        found |= PacketTriangle<kAny>(tris, first, count, g + uint32_t(__builtin_ctz(bits)), run, lanes, p);
  } else {
    for (uint32_t at = 0; at < count; ++at) found |= PacketTriangle<kAny>(tris, first, count, at, run, lanes, p);
  }
  return found;
}

// Any hit: a packet entry with at most this many live rays is traced one ray at a time (measured on the dragon's
// shadow rays, AVX2, wide8: 6 of 16 and 3 of 8 were best; 0 and "always single" were both ~25% slower).
template <size_t P>
constexpr int kSingleThreshold = P == 16 ? 6 : 3;
// Closest hit in per-lane mode (below): the same hand-over at half the packet (8 of 16 on bunny-16m, AVX2, wide8:
// 3.83 Mrays/s; 6: 3.6).
template <size_t P>
constexpr int kClosestSingleThreshold = int(P / 2);

// Closest-hit packets normally let interior children inherit the node's lanes once the packet's interval test
// passes them (cheap while the packet's rays stay together). When triangles are small against the packet's
// footprint the rays part early and the packet drags all its lanes through every subtree any of them enters:
// on the bunny grown to 16 M triangles (2.5 of 16 lanes reach an average leaf) that ran at 2.9 Mrays/s, slower
// than single rays (3.5). Such packets switch to per-lane child tests, which let lanes drop out, and hand
// subtrees with few lanes to single-ray traversal (3.85 Mrays/s). The switch is driven by leaf occupancy, the
// share of a packet's rays that reach the leaves it visits (13 of 16 on the bunny and dragon, 7 on bunny-1m, 4 on
// bunny-4m), two ways:
//   - within a packet, after two leaf visits below 40 % occupancy;
//   - from the start, when the running mean over the batch's earlier packets (started in interval mode) is below
//     25 %; every 64th packet starts in interval mode anyway, to keep that mean current.
// Both modes find the same closest hits (ties at exactly equal t may resolve differently); the thresholds were
// picked on bunny, dragon, bunny-1m, -4m and -16m primary rays, where no scene got slower (2026-11-22, 15:18 UTC).
constexpr float kSparseLeafOccupancy = 0.40f;
constexpr uint32_t kSparseLeafVisits = 2;
constexpr float kSparseBatchOccupancy = 0.25f;
constexpr size_t kIntervalProbeEvery = 64;

// Leaf occupancy of one closest-hit packet, and the mode it starts in.
struct PacketStats {
  uint32_t leaf_visits = 0, leaf_lanes = 0;
  bool per_lane = false;
  // A leaf, or a subtree handed to single rays (counted as one sparse leaf visit), reached by `lanes`.
  void count_leaf(uint32_t lanes) {
    ++leaf_visits;
    leaf_lanes += uint32_t(std::popcount(lanes));
  }
};

// `stats`: the closest-hit packet's leaf occupancy and mode (see PacketStats); any hit takes none (nullptr).
// `extent`: the tree's plane_extent, for the single-ray hand-over's constants.
template <int N, size_t P, bool kAny>
void TracePacket(const WideBvh<N>& bvh, const float extent[3], const TriangleLeaves& tris, Packet<P>& p,
                 PacketStats* stats) {
  struct Entry {
    uint32_t ref, count, lanes;
    float t_near;
  };
  Entry stack[kMaxWideDepth * (N - 1) + 1];
  int sp = 0;
  uint32_t ref = 0, count = 0, lanes = p.valid;  // the root is node 0
  bool per_lane = !kAny && stats->per_lane;  // closest hit: per-lane child tests and single-ray hand-over (above)
  const float valid_count = float(std::popcount(p.valid));
  // The single-ray kernel's constants of the packet's rays, made at the first hand-over (vector ops across the
  // rays), then shared by every later one: a packet hands some rays over several times (made per ray and per
  // hand-over they cost ~150 instructions each).
  RayBlock block;
  bool block_ready = false;
  if (!kAny && p.same_octant) {  // IntervalTriangles' margin (see there)
    float o_max = 0;
    for (int k = 0; k < 3; ++k) o_max = std::fmax(o_max, std::fmax(std::fabs(p.o_lo[k]), std::fabs(p.o_hi[k])));
    const float margin = 0x1p-20f * (std::fmax(extent[0], std::fmax(extent[1], extent[2])) + o_max);
    for (int k = 0; k < 3; ++k) p.tri_o_lo[k] = p.o_lo[k] - margin, p.tri_o_hi[k] = p.o_hi[k] + margin;
  }
  for (;;) {
    if ((kAny || per_lane) && std::popcount(lanes) <= (kAny ? kSingleThreshold<P> : kClosestSingleThreshold<P>)) {
      // Few rays left here: one at a time is cheaper than a mostly empty packet.
      if (!block_ready) {
        static_assert(P <= kRayBlock);
        SetupRays<N>(RaySoA{p.ox, p.oy, p.oz, p.dx, p.dy, p.dz, p.t_max}, 0, P, extent, block);
        block_ready = true;
      }
      for (uint32_t b = lanes; b != 0; b &= b - 1) {
        const size_t i = size_t(__builtin_ctz(b));
        const SingleRay one{&block, i, tris.data.data()};
        if constexpr (kAny) {
          if (TraceRay<N, true>(bvh, tris, one, p.t_max[i], nullptr, ref, count)) p.t_max[i] = -kInfinity;
        } else {
          Hit h;
          if (TraceRay<N, false>(bvh, tris, one, p.t_max[i], &h, ref, count)) {
            p.t_max[i] = h.t;
            p.b1[i] = h.b1;
            p.b2[i] = h.b2;
            p.prim[i] = h.prim;
          }
        }
      }
      if constexpr (kAny) {
        if (LiveLanes(p, p.valid) == 0) return;
      } else {
        stats->count_leaf(lanes);
        if (p.same_octant) p.t_hi = MaxT(p);
      }
    } else if (ref & kLeafFlag) {
      if constexpr (!kAny) {
        stats->count_leaf(lanes);
        if (!per_lane && stats->leaf_visits >= kSparseLeafVisits &&
            float(stats->leaf_lanes) < kSparseLeafOccupancy * float(stats->leaf_visits) * valid_count)
          per_lane = true;
      }
      // Any hit: stop once every ray is occluded.
      if (PacketLeaf<kAny>(tris, ref & ~kLeafFlag, count, lanes, p)) {
        if constexpr (kAny) {
          if (LiveLanes(p, p.valid) == 0) return;
        } else if (p.same_octant) {
          p.t_hi = MaxT(p);  // closest hit: the interval's far bound follows the shrinking t_max
        }
      }
    } else {
      const WideNode<N>& node = bvh.nodes[ref];
      uint32_t child_lanes[N];
      alignas(64) float t_near[N];
      uint32_t bits;
      if (!kAny && p.same_octant && !per_lane) {
        // Closest hit, one octant: the interval test alone decides the interior children, which inherit the
        // node's lanes and are ordered by the interval's entry bound (a lower bound of every lane's entry
        // distance, so the pop test below stays exact). Only leaf children get the per-lane test, so a leaf's
        // triangles are tested against the lanes that reach its box (and lane groups without any are skipped).
        const uint32_t cand = IntervalChildren(node, p, t_near) & NonEmptyChildren(node);
        const uint32_t leaf_cand = cand & LeafChildren(node);
        bits = cand & ~leaf_cand;
        FillLanes<N>(child_lanes, lanes);  // every slot: one vector store (a loop over the bits had 3 % of samples)
        if (leaf_cand != 0) {
          // Their order is the interval's entry bound as well: the smallest per-lane entry distance orders
          // them no better (measured: a reduction per leaf child cost 5 %, AVX3, 2026-11-23).
          bits |= PacketChildren<false>(node, p, lanes, leaf_cand, child_lanes, nullptr);
        }
      } else {
        uint32_t cand = ~0u;
        if (p.same_octant) cand = IntervalChildren(node, p);
        bits = cand == 0 ? 0 : PacketChildren<!kAny>(node, p, lanes, cand, child_lanes, t_near);
      }
      if (bits != 0) {
        if constexpr (kAny) {
          // Any order will do: descend into the first hit child, push the others.
          const uint32_t first = uint32_t(__builtin_ctz(bits));
          for (bits &= bits - 1; bits != 0; bits &= bits - 1) {
            const uint32_t c = uint32_t(__builtin_ctz(bits));
            stack[sp++] = {node.child[c], node.leaf_count[c], child_lanes[c], 0.0f};
          }
          ref = node.child[first], count = node.leaf_count[first], lanes = child_lanes[first];
          continue;
        }
        // Hit children far to near (insertion sort).
        uint32_t order[N];
        int n = 0;
        for (; bits != 0; bits &= bits - 1) {
          const uint32_t c = uint32_t(__builtin_ctz(bits));
          int j = n++;
          for (; j > 0 && t_near[order[j - 1]] < t_near[c]; --j) order[j] = order[j - 1];
          order[j] = c;
        }
        for (int k = 0; k < n - 1; ++k) {
          const uint32_t c = order[k];
          stack[sp++] = {node.child[c], node.leaf_count[c], child_lanes[c], t_near[c]};
          // The second nearest is the likeliest next pop: start loading it (+2 to 4 %, AVX3, 2026-11-23).
          if (k == n - 2) Prefetch<N>(bvh, tris.data.data(), node.child[c], node.leaf_count[c]);
        }
        const uint32_t c = order[n - 1];
        ref = node.child[c], count = node.leaf_count[c], lanes = child_lanes[c];
        continue;
      }
    }
    // Pop the next entry that still matters: for any hit, one with an unoccluded lane; for closest hit, one
    // whose entry distance some of its lanes' closest hit so far has not passed.
    for (;;) {
      if (sp == 0) return;
      const Entry& e = stack[--sp];
      uint32_t keep;
      if constexpr (kAny) {
        keep = LiveLanes(p, e.lanes);
      } else {
        keep = LanesReaching(p, e.lanes, e.t_near);
      }
      if (keep != 0) {
        ref = e.ref, count = e.count, lanes = keep;
        break;
      }
    }
  }
}

// Calls tracing at least this many rays write their Hits with non-temporal stores (when the array is 16-byte
// aligned): 20 bytes a ray, and ordinary stores first read every line they fill from memory. On a million camera
// rays of the bunny (AVX3, 2026-11-23) writing the Hits took 35 ns per packet of 16 with ordinary stores, 26 ns
// streamed, of about 450 ns (+2 % in all). Below this the Hits fit in the caches, where the caller finds them.
constexpr size_t kStreamHitsFrom = size_t(1) << 16;

#if HWY_TARGET <= HWY_AVX3
// AVX-512: a packet of 16 results becomes its 80 Hit words (5 per ray: t, prim, b1, b2, instance) by two-table
// permutes, 5 vectors of 16 words: word w of the packet is field w % 5 of ray w / 5. The scalar staging it
// replaces took 80 four-byte stores, whose 16-byte reloads for the streaming stores could not forward.
struct HitWordTables {
  alignas(64) int32_t t_prim[5][16];  // lane j of vector k: index into (t, prim) for fields 0 and 1
  alignas(64) int32_t b1_b2[5][16];   // and into (b1, b2) for fields 2 and 3
  uint16_t is_t_prim[5], is_b1_b2[5];  // lanes of those fields; the others are field 4, the instance (kNoHit)
};
constexpr HitWordTables MakeHitWordTables() {
  HitWordTables tab{};
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 16; ++j) {
      const int w = 16 * k + j, ray = w / 5, field = w % 5;
      tab.t_prim[k][j] = field == 1 ? 16 + ray : ray;
      tab.b1_b2[k][j] = field == 3 ? 16 + ray : ray;
      if (field < 2) tab.is_t_prim[k] |= uint16_t(1u << j);
      if (field == 2 || field == 3) tab.is_b1_b2[k] |= uint16_t(1u << j);
    }
  return tab;
}
HWY_INLINE void HitWords16(const Packet<16>& p, uint32_t* words) {
  static constexpr HitWordTables kTab = MakeHitWordTables();
  const __m512 t = _mm512_load_ps(p.t_max), b1 = _mm512_load_ps(p.b1), b2 = _mm512_load_ps(p.b2);
  const __m512 prim = _mm512_castsi512_ps(_mm512_load_si512(p.prim));
  const __m512 none = _mm512_castsi512_ps(_mm512_set1_epi32(int(kNoHit)));
  for (int k = 0; k < 5; ++k) {
    const __m512 x = _mm512_permutex2var_ps(t, _mm512_load_si512(kTab.t_prim[k]), prim);
    const __m512 y = _mm512_permutex2var_ps(b1, _mm512_load_si512(kTab.b1_b2[k]), b2);
    const __m512 out = _mm512_mask_blend_ps(kTab.is_b1_b2[k], _mm512_mask_blend_ps(kTab.is_t_prim[k], none, x), y);
    _mm512_store_ps(reinterpret_cast<float*>(words + 16 * k), out);
  }
}
#endif

// The packet's results as Hits: a miss keeps prim = kNoHit and b1 = b2 = 0 from SetupPacket and gets t = inf
// (its t_max may be finite). Branch-free, the t select as one vector op. A whole packet (n == P) is staged as its
// 5 P words when it is streamed (`stream`, see kStreamHitsFrom; the caller flushes) or, on AVX-512 (HitWords16),
// always: there the words are five vectors, copied out with moves that forward from their stores.
template <size_t P>
HWY_INLINE void WriteHits(Packet<P>& p, size_t n, Hit* hits, bool stream) {
  const hn::CappedTag<float, P> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  for (size_t g = 0; g < P; g += hn::Lanes(d)) {
    const auto miss = hn::RebindMask(d, hn::Eq(hn::Load(du, p.prim + g), hn::Set(du, kNoHit)));
    hn::Store(hn::IfThenElse(miss, hn::Set(d, kInfinity), hn::Load(d, p.t_max + g)), d, p.t_max + g);
  }
  static_assert(sizeof(Hit) == 5 * sizeof(uint32_t) && offsetof(Hit, instance) == 16);
#if HWY_TARGET <= HWY_AVX3
  constexpr bool kVectorWords = P == 16;
#else
  constexpr bool kVectorWords = false;
#endif
  if (n == P && (stream || kVectorWords)) {
    alignas(64) uint32_t words[5 * P];
#if HWY_TARGET <= HWY_AVX3
    if constexpr (kVectorWords) HitWords16(p, words);
#endif
    if constexpr (!kVectorWords) {
      for (size_t i = 0; i < P; ++i) {
        std::memcpy(&words[5 * i], &p.t_max[i], 4);
        words[5 * i + 1] = p.prim[i];
        std::memcpy(&words[5 * i + 2], &p.b1[i], 4);
        std::memcpy(&words[5 * i + 3], &p.b2[i], 4);
        words[5 * i + 4] = kNoHit;  // instance
      }
    }
    if (stream) {
      const hn::CappedTag<uint32_t, 4> d4;
      uint32_t* const out = reinterpret_cast<uint32_t*>(hits);  // 16-byte aligned (checked by the caller)
      for (size_t k = 0; k < 5 * P; k += hn::Lanes(d4)) hn::Stream(hn::Load(d4, words + k), d4, out + k);
    } else {
      std::memcpy(static_cast<void*>(hits), words, sizeof(words));
    }
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    Hit h;
    h.t = p.t_max[i], h.prim = p.prim[i], h.b1 = p.b1[i], h.b2 = p.b2[i];
    hits[i] = h;
  }
}

template <int N, size_t P>
void ClosestPackets(const WideBvh<N>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                    Hit* hits) {
  Packet<P> p;
  float extent[3];  // for the single-ray hand-over's constants
  traverse_detail::plane_extent(bvh, extent);
  float occupancy = 1.0f;  // running mean leaf occupancy of the packets started in interval mode
  // Every packet's Hits start 20 P bytes after the previous one's: 16-byte aligned when the array is.
  const bool stream = count >= kStreamHitsFrom && reinterpret_cast<uintptr_t>(hits) % 16 == 0;
  for (size_t begin = 0; begin < count; begin += P) {
    const size_t n = count - begin < P ? count - begin : P;
    SetupPacket<N, true>(p, rays, begin, n);
    traverse_detail::prefetch_rays(rays, begin + traverse_detail::kRayPrefetchAhead, count);
    PacketStats stats;
    stats.per_lane = (begin / P) % kIntervalProbeEvery != 0 && occupancy < kSparseBatchOccupancy;
    if (p.valid != 0 && !bvh.nodes.empty()) TracePacket<N, P, false>(bvh, extent, tris, p, &stats);
    if (!stats.per_lane && stats.leaf_visits > 0)
      occupancy = 0.9f * occupancy +
                  0.1f * float(stats.leaf_lanes) / (float(stats.leaf_visits) * float(std::popcount(p.valid)));
    WriteHits(p, n, hits + begin, stream);
  }
  if (stream) hwy::FlushStream();
}

template <int N, size_t P>
void AnyPackets(const WideBvh<N>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                uint8_t* occluded) {
  Packet<P> p;
  float extent[3];  // for the single-ray hand-over's constants
  traverse_detail::plane_extent(bvh, extent);
  for (size_t begin = 0; begin < count; begin += P) {
    const size_t n = count - begin < P ? count - begin : P;
    SetupPacket<N, true>(p, rays, begin, n);
    traverse_detail::prefetch_rays(rays, begin + traverse_detail::kRayPrefetchAhead, count);
    if (p.valid != 0 && !bvh.nodes.empty()) TracePacket<N, P, true>(bvh, extent, tris, p, nullptr);
    // Occluded lanes were retired with t_max = -inf; invalid ones never were valid.
    for (size_t i = 0; i < n; ++i) occluded[begin + i] = ((p.valid >> i) & 1) && !(p.t_max[i] > 0) ? 1 : 0;
  }
}

}  // namespace

// Exported per target; packet_size is 8 or 16 (checked by the callers below).
void ClosestPackets4(const WideBvh<4>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, Hit* h, int ps) {
  ps == 16 ? ClosestPackets<4, 16>(b, t, r, n, h) : ClosestPackets<4, 8>(b, t, r, n, h);
}
void ClosestPackets8(const WideBvh<8>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, Hit* h, int ps) {
  ps == 16 ? ClosestPackets<8, 16>(b, t, r, n, h) : ClosestPackets<8, 8>(b, t, r, n, h);
}
void AnyPackets4(const WideBvh<4>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, uint8_t* o, int ps) {
  ps == 16 ? AnyPackets<4, 16>(b, t, r, n, o) : AnyPackets<4, 8>(b, t, r, n, o);
}
void AnyPackets8(const WideBvh<8>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, uint8_t* o, int ps) {
  ps == 16 ? AnyPackets<8, 16>(b, t, r, n, o) : AnyPackets<8, 8>(b, t, r, n, o);
}

}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

static_assert(kMaxBvhDepth <= traverse_detail::kMaxWideDepth, "traversal stacks are sized for the builder's depth");

HWY_EXPORT(ClosestPackets4);
HWY_EXPORT(ClosestPackets8);
HWY_EXPORT(AnyPackets4);
HWY_EXPORT(AnyPackets8);

namespace {
void check_packet_size(int packet_size) {
  if (packet_size != 8 && packet_size != 16)
    throw Error("Ray packets hold 8 or 16 rays, not " + std::to_string(packet_size) + ".");
}
}  // namespace

void intersect_closest_packets(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                               Hit* hits, int packet_size) {
  check_packet_size(packet_size);
  HWY_DYNAMIC_DISPATCH(ClosestPackets4)(bvh, tris, rays, count, hits, packet_size);
}
void intersect_closest_packets(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                               Hit* hits, int packet_size) {
  check_packet_size(packet_size);
  HWY_DYNAMIC_DISPATCH(ClosestPackets8)(bvh, tris, rays, count, hits, packet_size);
}
void intersect_any_packets(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                           uint8_t* occluded, int packet_size) {
  check_packet_size(packet_size);
  HWY_DYNAMIC_DISPATCH(AnyPackets4)(bvh, tris, rays, count, occluded, packet_size);
}
void intersect_any_packets(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                           uint8_t* occluded, int packet_size) {
  check_packet_size(packet_size);
  HWY_DYNAMIC_DISPATCH(AnyPackets8)(bvh, tris, rays, count, occluded, packet_size);
}

}  // namespace torte
#endif  // HWY_ONCE
