// A packet of P = 8 or 16 rays for the packet traversal kernels (traverse_packet.cc): its per-lane state
// (structure of arrays, lanes = rays), its set-up from a RaySoA (validity, watertight-test constants, the shared
// octant and permutation, the interval bounds for interval culling) and queries over its lanes. Include after
// traverse-inl.h (per-target part) inside a foreach_target file compiled without FMA contraction.

// Per-target include guard (Highway's pattern).
#if defined(TORTE_SIMD_PACKET_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_PACKET_INL_H_TARGET
#undef TORTE_SIMD_PACKET_INL_H_TARGET
#else
#define TORTE_SIMD_PACKET_INL_H_TARGET
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

#include "accel/hit.h"
#include "core/ray.h"
#include "traverse-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

// Per-lane state of a packet, structure of arrays so each field loads as one vector per lane group. Lane masks
// are stored as floats that are all ones (true) or zero, and read back with MaskFromVec.
template <size_t P>
struct Packet {
  alignas(64) float ox[P], oy[P], oz[P], dx[P], dy[P], dz[P];  // the rays (stand-ins in invalid lanes)
  alignas(64) float ix[P], iy[P], iz[P];                       // slab test: 1 / direction
  alignas(64) float neg[3][P];                                 // direction component negative (mask)
  alignas(64) float okx[P], oky[P], okz[P];                    // origin permuted to the lane's (kx, ky, kz)
  alignas(64) float sx[P], sy[P], sz[P];                       // shear of the watertight test
  alignas(64) float axis_is[3][2][P];  // axis_is[k][a]: the lane's k-th permuted axis (kx, ky, kz) equals a (mask)
  alignas(64) float t_max[P];          // shrinks to the closest hit; -inf for lanes that are done
  alignas(64) float b1[P], b2[P];
  alignas(64) uint32_t prim[P];
  uint32_t valid;               // lanes holding a valid ray
  bool same_octant, same_axes;  // over the valid lanes: one direction octant / one axis permutation
  uint32_t near_off[3], far_off[3];  // when same_octant: plane offsets into a node, as in the single-ray kernel
  int axes[3];                       // when same_axes: kx, ky, kz
  // Interval culling (Reshetov et al. 2005), when same_octant: bounds over the valid lanes of the origin and of
  // 1 / direction per axis, and of t_max. Axes where some lane's 1 / direction is infinite are left out
  // (interval_axes bit a clear), which only makes the test more conservative.
  float o_lo[3], o_hi[3], i_lo[3], i_hi[3], t_hi;
  uint32_t interval_axes;
  float tri_o_lo[3], tri_o_hi[3];  // IntervalTriangles: the origin bounds widened by a margin (set by the traversal)
  Ray ray(size_t i) const { return {{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, t_max[i]}; }
};

// Loads rays [begin, begin + n) (n <= P) into the packet: validity as traverse_detail::is_valid_ray decides it, and
// the per-ray setup of the watertight test computed lane by lane exactly as WatertightRay's constructor does
// (same axis choice and tie rule, same divisions), so the leaf test takes the scalar test's decisions.
template <int N, bool kIntervals, size_t P>
HWY_INLINE void SetupPacket(Packet<P>& p, const RaySoA& rays, size_t begin, size_t n) {
  const hn::CappedTag<float, P> d;
  const size_t L = hn::Lanes(d);
  alignas(64) float tail[7][P];
  const float* src[7];
  traverse_detail::ray_sources(rays, begin, n, tail, src);  // a partial packet: padding lanes are invalid
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  p.valid = 0;
  // Per-axis lane bits (lane i -> bit i) of the direction signs and of the permutation, and the interval bounds
  // over the valid lanes, gathered as the lane groups go by.
  uint32_t neg_bits[3] = {0, 0, 0}, axis_bits[3][2] = {{0, 0}, {0, 0}, {0, 0}}, inf_bits[3] = {0, 0, 0};
  const auto pinf = hn::Set(d, kInfinity), ninf = hn::Set(d, -kInfinity);
  hn::Vec<decltype(d)> o_lo[3] = {pinf, pinf, pinf}, o_hi[3] = {ninf, ninf, ninf};
  hn::Vec<decltype(d)> i_lo[3] = {pinf, pinf, pinf}, i_hi[3] = {ninf, ninf, ninf};
  auto t_hi = ninf;
  for (size_t g = 0; g < P; g += L) {
    auto ox = hn::LoadU(d, src[0] + g), oy = hn::LoadU(d, src[1] + g), oz = hn::LoadU(d, src[2] + g);
    auto dx = hn::LoadU(d, src[3] + g), dy = hn::LoadU(d, src[4] + g), dz = hn::LoadU(d, src[5] + g);
    auto t_max = hn::LoadU(d, src[6] + g);
    const auto valid = ValidRayLanes(d, ox, oy, oz, dx, dy, dz, t_max);
    p.valid |= MaskBits(d, valid) << g;
    // Invalid lanes become a harmless stand-in whose t_max = -inf keeps it out of every test.
    ox = hn::IfThenElseZero(valid, ox), oy = hn::IfThenElseZero(valid, oy), oz = hn::IfThenElseZero(valid, oz);
    dx = hn::IfThenElse(valid, dx, one), dy = hn::IfThenElse(valid, dy, one), dz = hn::IfThenElse(valid, dz, one);
    t_max = hn::IfThenElse(valid, t_max, hn::Set(d, -kInfinity));
    hn::Store(ox, d, p.ox + g), hn::Store(oy, d, p.oy + g), hn::Store(oz, d, p.oz + g);
    hn::Store(dx, d, p.dx + g), hn::Store(dy, d, p.dy + g), hn::Store(dz, d, p.dz + g);
    hn::Store(t_max, d, p.t_max + g);
    const auto ix = hn::Div(one, dx), iy = hn::Div(one, dy), iz = hn::Div(one, dz);
    hn::Store(ix, d, p.ix + g), hn::Store(iy, d, p.iy + g), hn::Store(iz, d, p.iz + g);
    const auto neg_x = hn::Lt(ix, zero), neg_y = hn::Lt(iy, zero), neg_z = hn::Lt(iz, zero);
    hn::Store(hn::VecFromMask(d, neg_x), d, p.neg[0] + g);  // as SlabRay: by the sign of 1 / d
    hn::Store(hn::VecFromMask(d, neg_y), d, p.neg[1] + g);
    hn::Store(hn::VecFromMask(d, neg_z), d, p.neg[2] + g);
    neg_bits[0] |= MaskBits(d, neg_x) << g, neg_bits[1] |= MaskBits(d, neg_y) << g;
    neg_bits[2] |= MaskBits(d, neg_z) << g;
    if constexpr (kIntervals) {  // bounds over the valid lanes only
      const hn::Vec<decltype(d)> o[3] = {ox, oy, oz}, inv[3] = {ix, iy, iz};
      for (int k = 0; k < 3; ++k) {
        o_lo[k] = hn::Min(o_lo[k], hn::IfThenElse(valid, o[k], pinf));
        o_hi[k] = hn::Max(o_hi[k], hn::IfThenElse(valid, o[k], ninf));
        i_lo[k] = hn::Min(i_lo[k], hn::IfThenElse(valid, inv[k], pinf));
        i_hi[k] = hn::Max(i_hi[k], hn::IfThenElse(valid, inv[k], ninf));
        inf_bits[k] |= MaskBits(d, hn::AndNot(hn::IsFinite(inv[k]), valid)) << g;
      }
      t_hi = hn::Max(t_hi, t_max);  // invalid lanes hold -inf
    }
    const auto w = SetupWatertight(d, dx, dy, dz, ix, iy, iz);
    hn::Store(w.s[0], d, p.sx + g), hn::Store(w.s[1], d, p.sy + g), hn::Store(w.s[2], d, p.sz + g);
    const auto& axis_is = w.axis_is;
    hn::Store(Pick(axis_is[0][0], axis_is[0][1], ox, oy, oz), d, p.okx + g);
    hn::Store(Pick(axis_is[1][0], axis_is[1][1], ox, oy, oz), d, p.oky + g);
    hn::Store(Pick(axis_is[2][0], axis_is[2][1], ox, oy, oz), d, p.okz + g);
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 2; ++a) {
        hn::Store(hn::VecFromMask(d, axis_is[k][a]), d, p.axis_is[k][a] + g);
        axis_bits[k][a] |= MaskBits(d, axis_is[k][a]) << g;
      }
    hn::Store(zero, d, p.b1 + g), hn::Store(zero, d, p.b2 + g);
  }
  for (size_t i = 0; i < P; ++i) p.prim[i] = kNoHit;
  if (p.valid == 0) return;
  // Shared octant / permutation: every valid lane agrees with the first one.
  const uint32_t valid = p.valid, lead = valid & (0u - valid);
  auto uniform = [valid](uint32_t bits) { return (bits & valid) == 0 || (bits & valid) == valid; };
  p.same_octant = p.same_axes = true;
  for (int k = 0; k < 3; ++k) {
    const bool neg = (neg_bits[k] & lead) != 0;
    p.near_off[k] = traverse_detail::bound_offset<N>(k, neg);
    p.far_off[k] = traverse_detail::bound_offset<N>(k, !neg);
    p.axes[k] = (axis_bits[k][0] & lead) ? 0 : (axis_bits[k][1] & lead) ? 1 : 2;
    p.same_octant &= uniform(neg_bits[k]);
    p.same_axes &= uniform(axis_bits[k][0]) && uniform(axis_bits[k][1]);
  }
  p.interval_axes = 0;
  p.t_hi = -kInfinity;
  if (!kIntervals || !p.same_octant) return;  // interval culling: same-octant packets only
  for (int k = 0; k < 3; ++k) {
    p.o_lo[k] = hn::GetLane(hn::MinOfLanes(d, o_lo[k])), p.o_hi[k] = hn::GetLane(hn::MaxOfLanes(d, o_hi[k]));
    p.i_lo[k] = hn::GetLane(hn::MinOfLanes(d, i_lo[k])), p.i_hi[k] = hn::GetLane(hn::MaxOfLanes(d, i_hi[k]));
    if (inf_bits[k] == 0) p.interval_axes |= 1u << k;
  }
  p.t_hi = hn::GetLane(hn::MaxOfLanes(d, t_hi));
}

template <class D>
HWY_INLINE uint32_t GroupMask(D d) {
  return hn::MaxLanes(d) >= 32 ? ~0u : (1u << hn::MaxLanes(d)) - 1;
}

// Lanes still live (t_max > 0) among `lanes`.
template <size_t P>
HWY_INLINE uint32_t LiveLanes(const Packet<P>& p, uint32_t lanes) {
  const hn::CappedTag<float, P> d;
  const size_t L = hn::Lanes(d);
  uint32_t live = 0;
  for (size_t g = 0; g < P; g += L) live |= MaskBits(d, hn::Gt(hn::Load(d, p.t_max + g), hn::Zero(d))) << g;
  return live & lanes;
}

// Largest t_max over the packet's lanes (done lanes hold -inf): the far bound of the interval test.
template <size_t P>
HWY_INLINE float MaxT(const Packet<P>& p) {
  const hn::CappedTag<float, P> d;
  const size_t L = hn::Lanes(d);
  auto m = hn::Load(d, p.t_max);
  for (size_t g = L; g < P; g += L) m = hn::Max(m, hn::Load(d, p.t_max + g));
  return hn::GetLane(hn::MaxOfLanes(d, m));
}

// Lanes among `lanes` whose closest hit so far is not nearer than t.
template <size_t P>
HWY_INLINE uint32_t LanesReaching(const Packet<P>& p, uint32_t lanes, float t) {
  const hn::CappedTag<float, P> d;
  const size_t L = hn::Lanes(d);
  uint32_t keep = 0;
  for (size_t g = 0; g < P; g += L) keep |= MaskBits(d, hn::Le(hn::Set(d, t), hn::Load(d, p.t_max + g))) << g;
  return keep & lanes;
}

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_PACKET_INL_H_TARGET
