// The per-ray constants of the single-ray traversal kernel (traverse_single-inl.h), computed for a block of rays
// at a time with vector ops across the rays (lanes = rays), then read by the kernel one ray at a time.
//
// Why a block: built one ray at a time, the constants (origin, inverse direction, near/far plane offsets, the
// watertight test's axis permutation and shear) cost ~150 instructions per ray, 15 % of a diffuse ray's traversal
// (callgrind, 2026-11-22), mostly scalar divisions, selects and stores; across 8 rays per vector they cost a few.
// Every value is the one the scalar code computes (WatertightRay, SlabRay), bit for bit: the same IEEE divisions
// and products, and selects instead of branches. SetupRay is the one-ray version, the reference the tests compare
// SetupRays against (CountRaySetupMismatches). The packet kernels build a block for a packet the first time they
// hand rays over to single-ray traversal. Include after traverse-inl.h (per-target part) inside a foreach_target
// file.

// Per-target include guard (Highway's pattern).
#if defined(TORTE_SIMD_SINGLE_RAY_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
#undef TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
#else
#define TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
#endif

#include <hwy/highway.h>

#include <cmath>
#include <cstdint>

#include "accel/hit.h"
#include "geometry/triangle.h"
#include "traverse-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

// Rays per block: a multiple of every target's float lane count (at most 16).
constexpr size_t kRayBlock = 16;

// Constants of up to kRayBlock rays, structure of arrays (index = ray), 64-byte aligned arrays: 2,048 bytes.
struct RayBlock {
  alignas(64) float o[3][kRayBlock];          // origin
  alignas(64) float inv_d[3][kRayBlock];      // 1 / direction (-0 gives -inf)
  alignas(64) float inv_d_far[3][kRayBlock];  // exact slab test: inv_d * kFarRound, the far rounding folded in
  alignas(64) float org_near[3][kRayBlock];   // FMA slab test: o * inv_d + margin (traverse_detail::kSlabMargin)
  alignas(64) float org_far[3][kRayBlock];    // ... and o * inv_d - margin
  alignas(64) uint32_t near_off[3][kRayBlock];  // per axis, node_floats offset of the entry plane array
  alignas(64) uint32_t far_off[3][kRayBlock];   // ... and of the exit plane array
  alignas(64) int32_t k[3][kRayBlock];        // watertight test: axes kx, ky, kz (WatertightRay)
  alignas(64) float ok[3][kRayBlock];         // origin on those axes: o[kx], o[ky], o[kz]
  alignas(64) float s[3][kRayBlock];          // shear sx, sy, sz
  alignas(64) float t_max[kRayBlock];
  uint32_t valid = 0;      // bit j: ray j can hit something (traverse_detail::is_valid_ray)
  uint32_t fma_slabs = 0;  // bit j: ray j takes the FMA slab test (traverse_detail::fma_slab_axis)
};
static_assert(sizeof(RayBlock) == 2048);

// One ray of a RayBlock, as the kernel sees it.
struct SingleRay {
  const RayBlock* b;
  size_t j;
  const float* leaf_data;  // TriangleLeaves::data

  float o(int a) const { return b->o[a][j]; }
  float inv_d(int a) const { return b->inv_d[a][j]; }
  float inv_d_far(int a) const { return b->inv_d_far[a][j]; }
  float org_near(int a) const { return b->org_near[a][j]; }
  float org_far(int a) const { return b->org_far[a][j]; }
  bool fma_slabs() const { return (b->fma_slabs >> j) & 1; }
  uint32_t near_off(int a) const { return b->near_off[a][j]; }
  uint32_t far_off(int a) const { return b->far_off[a][j]; }
  int k(int a) const { return b->k[a][j]; }
  float ok(int a) const { return b->ok[a][j]; }
  float s(int a) const { return b->s[a][j]; }
  // The scalar test's per-ray part, for the rare lanes it decides.
  WatertightRay watertight() const {
    WatertightRay wr;
    wr.o = {o(0), o(1), o(2)};
    wr.kx = k(0);
    wr.ky = k(1);
    wr.kz = k(2);
    wr.sx = s(0);
    wr.sy = s(1);
    wr.sz = s(2);
    wr.t_max = b->t_max[j];
    wr.valid = true;  // a valid ray's dominant direction component is not 0
    return wr;
  }
};

// Entry j of `b` from one ray, with the scalar code itself (the reference for SetupRays).
// `extent`: the tree's plane_extent.
template <int N>
HWY_INLINE void SetupRay(const Ray& ray, const float extent[3], RayBlock& b, size_t j) {
  const WatertightRay wr(ray);
  bool fma = true;
  const int k[3] = {wr.kx, wr.ky, wr.kz};
  const float s[3] = {wr.sx, wr.sy, wr.sz};
  for (int a = 0; a < 3; ++a) {
    b.o[a][j] = ray.o[a];
    b.inv_d[a][j] = 1.0f / ray.d[a];
    b.inv_d_far[a][j] = b.inv_d[a][j] * traverse_detail::kFarRound;
    const float scale = std::fabs(b.inv_d[a][j]) * (extent[a] + std::fabs(ray.o[a]));
    const float scaled = scale * traverse_detail::kSlabMargin;  // x86 max: the floor unless scaled is greater
    const float margin = scaled > traverse_detail::kMinSlabMargin ? scaled : traverse_detail::kMinSlabMargin;
    b.org_near[a][j] = ray.o[a] * b.inv_d[a][j] + margin;
    b.org_far[a][j] = ray.o[a] * b.inv_d[a][j] - margin;
    fma = fma && traverse_detail::fma_slab_axis(b.inv_d[a][j], scale);
    const bool neg = b.inv_d[a][j] < 0;  // as SlabRay: -0 gives -inf, i.e. "negative"
    b.near_off[a][j] = traverse_detail::bound_offset<N>(a, neg);
    b.far_off[a][j] = traverse_detail::bound_offset<N>(a, !neg);
    b.k[a][j] = k[a];
    b.ok[a][j] = ray.o[k[a]];
    b.s[a][j] = s[a];
  }
  b.t_max[j] = ray.t_max;
  b.valid |= uint32_t(traverse_detail::is_valid_ray(ray)) << j;
  b.fma_slabs |= uint32_t(fma) << j;
}

// Entries [0, n) of `b` from rays [first, first + n) of `rays` (n <= kRayBlock), kRayBlock / lanes vectors.
template <int N>
HWY_INLINE void SetupRays(const RaySoA& rays, size_t first, size_t n, const float extent[3], RayBlock& b) {
  const hn::CappedTag<float, kRayBlock> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::RebindToUnsigned<decltype(d)> du;
  const size_t L = hn::Lanes(d);
  alignas(64) float tail[7][kRayBlock];
  const float* src[7];
  traverse_detail::ray_sources(rays, first, n, tail, src);  // a short last block: padding rays are invalid
  const auto zero = hn::Zero(d);
  const auto one = hn::Set(d, 1.0f);
  const auto abs_limit = hn::Set(d, traverse_detail::kMaxSlabScale);
  const auto inv_floor = hn::Set(d, traverse_detail::kMinInvDir);
  uint32_t valid = 0, fma_slabs = 0;
  for (size_t g = 0; g < n; g += L) {
    const hn::Vec<decltype(d)> o[3] = {hn::LoadU(d, src[0] + g), hn::LoadU(d, src[1] + g), hn::LoadU(d, src[2] + g)};
    const hn::Vec<decltype(d)> dir[3] = {hn::LoadU(d, src[3] + g), hn::LoadU(d, src[4] + g),
                                         hn::LoadU(d, src[5] + g)};
    const auto t_max = hn::LoadU(d, src[6] + g);
    valid |= MaskBits(d, ValidRayLanes(d, o[0], o[1], o[2], dir[0], dir[1], dir[2], t_max)) << g;
    const hn::Vec<decltype(d)> inv_d[3] = {hn::Div(one, dir[0]), hn::Div(one, dir[1]), hn::Div(one, dir[2])};
    const auto w = SetupWatertight(d, dir[0], dir[1], dir[2], inv_d[0], inv_d[1], inv_d[2]);
    auto fma = hn::FirstN(d, L);
    for (int a = 0; a < 3; ++a) {
      hn::Store(o[a], d, b.o[a] + g);
      const auto inv = inv_d[a];
      hn::Store(inv, d, b.inv_d[a] + g);
      hn::Store(hn::Mul(inv, hn::Set(d, traverse_detail::kFarRound)), d, b.inv_d_far[a] + g);
      const auto scale = hn::Mul(hn::Abs(inv), hn::Add(hn::Set(d, extent[a]), hn::Abs(o[a])));
      // Max with the floor second: a NaN scale (then not an FMA ray) gives the floor, as SetupRay does.
      const auto margin = hn::Max(hn::Mul(scale, hn::Set(d, traverse_detail::kSlabMargin)),
                                  hn::Set(d, traverse_detail::kMinSlabMargin));
      const auto org_inv = hn::Mul(o[a], inv);
      hn::Store(hn::Add(org_inv, margin), d, b.org_near[a] + g);
      hn::Store(hn::Sub(org_inv, margin), d, b.org_far[a] + g);
      fma = hn::And(fma, hn::And(hn::Lt(scale, abs_limit), hn::Gt(hn::Abs(inv), inv_floor)));
      const auto neg = hn::RebindMask(du, hn::Lt(inv, zero));
      const auto lo = hn::Set(du, traverse_detail::bound_offset<N>(a, false));
      const auto hi = hn::Set(du, traverse_detail::bound_offset<N>(a, true));
      hn::Store(hn::IfThenElse(neg, hi, lo), du, b.near_off[a] + g);
      hn::Store(hn::IfThenElse(neg, lo, hi), du, b.far_off[a] + g);
      const auto is0 = w.axis_is[a][0], is1 = w.axis_is[a][1];
      hn::Store(Pick(hn::RebindMask(di, is0), hn::RebindMask(di, is1), hn::Zero(di), hn::Set(di, 1), hn::Set(di, 2)),
                di, b.k[a] + g);
      hn::Store(Pick(is0, is1, o[0], o[1], o[2]), d, b.ok[a] + g);
      hn::Store(w.s[a], d, b.s[a] + g);
    }
    hn::Store(t_max, d, b.t_max + g);
    fma_slabs |= MaskBits(d, fma) << g;
  }
  b.valid = valid & ((1u << n) - 1);  // n <= 16
  b.fma_slabs = fma_slabs & ((1u << n) - 1);
}

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
