// The per-ray constants of the single-ray traversal kernel (traverse_single-inl.h), computed for a block of rays
// at a time with vector ops across the rays (lanes = rays), then read by the kernel one ray at a time.
//
// Why a block: built one ray at a time, the constants (origin, inverse direction, near/far plane offsets, the
// watertight test's axis permutation and shear) cost ~150 instructions per ray, 15 % of a diffuse ray's traversal
// (callgrind, 2026-11-22), mostly scalar divisions, selects and stores; across 8 rays per vector they cost a few.
// Every value is the one the scalar code computes (WatertightRay, SlabRay), bit for bit: the same IEEE divisions
// and products, and selects instead of branches. SetupRay is the one-ray version, for the packet kernels'
// single-ray fallback. Include after traverse-inl.h (per-target part) inside a foreach_target file.

// Per-target include guard (Highway's pattern).
#if defined(TORTE_SIMD_SINGLE_RAY_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
#undef TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
#else
#define TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "accel/hit.h"
#include "geometry/triangle.h"
#include "traverse-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

// Rays per block: a multiple of every target's float lane count (at most 16).
constexpr size_t kRayBlock = 16;

// Constants of up to kRayBlock rays, structure of arrays (index = ray), 64-byte aligned arrays: 1,664 bytes.
struct RayBlock {
  alignas(64) float o[3][kRayBlock];          // origin
  alignas(64) float inv_d[3][kRayBlock];      // 1 / direction (-0 gives -inf)
  alignas(64) float inv_d_far[3][kRayBlock];  // inv_d * kFarRound: the far planes' rounding folded in
  alignas(64) uint32_t near_off[3][kRayBlock];  // per axis, node_floats offset of the entry plane array
  alignas(64) uint32_t far_off[3][kRayBlock];   // ... and of the exit plane array
  alignas(64) int32_t k[3][kRayBlock];        // watertight test: axes kx, ky, kz (WatertightRay)
  alignas(64) float ok[3][kRayBlock];         // origin on those axes: o[kx], o[ky], o[kz]
  alignas(64) float s[3][kRayBlock];          // shear sx, sy, sz
  alignas(64) float t_max[kRayBlock];
  uint32_t valid = 0;  // bit j: ray j can hit something (traverse_detail::is_valid_ray)
};
static_assert(sizeof(RayBlock) == 1664);

// One ray of a RayBlock, as the kernel sees it.
struct SingleRay {
  const RayBlock* b;
  size_t j;
  const float* leaf_data;  // TriangleLeaves::data

  float o(int a) const { return b->o[a][j]; }
  float inv_d(int a) const { return b->inv_d[a][j]; }
  float inv_d_far(int a) const { return b->inv_d_far[a][j]; }
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
template <int N>
HWY_INLINE void SetupRay(const Ray& ray, RayBlock& b, size_t j) {
  const WatertightRay wr(ray);
  const int k[3] = {wr.kx, wr.ky, wr.kz};
  const float s[3] = {wr.sx, wr.sy, wr.sz};
  for (int a = 0; a < 3; ++a) {
    b.o[a][j] = ray.o[a];
    b.inv_d[a][j] = 1.0f / ray.d[a];
    b.inv_d_far[a][j] = b.inv_d[a][j] * traverse_detail::kFarRound;
    const bool neg = b.inv_d[a][j] < 0;  // as SlabRay: -0 gives -inf, i.e. "negative"
    b.near_off[a][j] = traverse_detail::bound_offset<N>(a, neg);
    b.far_off[a][j] = traverse_detail::bound_offset<N>(a, !neg);
    b.k[a][j] = k[a];
    b.ok[a][j] = ray.o[k[a]];
    b.s[a][j] = s[a];
  }
  b.t_max[j] = ray.t_max;
  b.valid |= uint32_t(traverse_detail::is_valid_ray(ray)) << j;
}

// Lane-wise v[k]: picks x, y or z by the axis index k (0, 1, 2).
template <class D, class DI, class V = hn::Vec<D>>
HWY_INLINE V SelectAxis(D d, DI di, hn::Vec<DI> k, V x, V y, V z) {
  return hn::IfThenElse(hn::RebindMask(d, hn::Eq(k, hn::Zero(di))), x,
                        hn::IfThenElse(hn::RebindMask(d, hn::Eq(k, hn::Set(di, 1))), y, z));
}

// Entries [0, n) of `b` from rays [first, first + n) of `rays` (n <= kRayBlock), kRayBlock / lanes vectors.
template <int N>
HWY_INLINE void SetupRays(const RaySoA& rays, size_t first, size_t n, RayBlock& b) {
  const hn::CappedTag<float, kRayBlock> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::RebindToUnsigned<decltype(d)> du;
  const size_t L = hn::Lanes(d);
  const float* src[7] = {rays.ox + first, rays.oy + first, rays.oz + first, rays.dx + first,
                         rays.dy + first, rays.dz + first, rays.t_max + first};
  alignas(64) float tail[7][kRayBlock];
  if (n < kRayBlock) {
    // A short last block: copy it, padded with zero rays (invalid), so every vector load stays in bounds.
    for (int c = 0; c < 7; ++c) {
      std::fill(tail[c], tail[c] + kRayBlock, 0.0f);
      std::memcpy(tail[c], src[c], n * sizeof(float));
      src[c] = tail[c];
    }
  }
  const auto zero = hn::Zero(d);
  const auto one = hn::Set(d, 1.0f);
  uint32_t valid = 0;
  for (size_t g = 0; g < n; g += L) {
    const hn::Vec<decltype(d)> o[3] = {hn::LoadU(d, src[0] + g), hn::LoadU(d, src[1] + g), hn::LoadU(d, src[2] + g)};
    const hn::Vec<decltype(d)> dir[3] = {hn::LoadU(d, src[3] + g), hn::LoadU(d, src[4] + g),
                                         hn::LoadU(d, src[5] + g)};
    const auto t_max = hn::LoadU(d, src[6] + g);
    // traverse_detail::is_valid_ray: finite origin and direction, a non-zero direction, t_max > 0 (false for NaN).
    auto ok_ray = hn::And(hn::And(hn::IsFinite(o[0]), hn::IsFinite(o[1])), hn::IsFinite(o[2]));
    ok_ray = hn::And(ok_ray, hn::And(hn::And(hn::IsFinite(dir[0]), hn::IsFinite(dir[1])), hn::IsFinite(dir[2])));
    const auto zero_dir = hn::And(hn::And(hn::Eq(dir[0], zero), hn::Eq(dir[1], zero)), hn::Eq(dir[2], zero));
    ok_ray = hn::AndNot(zero_dir, hn::And(ok_ray, hn::Gt(t_max, zero)));
    valid |= MaskBits(d, ok_ray) << g;

    // WatertightRay: kz = max_dimension(abs(d)), kx and ky cyclically after it, swapped for a negative d[kz].
    const auto ax = hn::Abs(dir[0]), ay = hn::Abs(dir[1]), az = hn::Abs(dir[2]);
    const auto x_over_y = hn::Gt(ax, ay);
    const auto kz_is_z = hn::Not(hn::Gt(hn::IfThenElse(x_over_y, ax, ay), az));
    const auto kz = hn::IfThenElse(hn::RebindMask(di, kz_is_z), hn::Set(di, 2),
                                   hn::IfThenElse(hn::RebindMask(di, x_over_y), hn::Zero(di), hn::Set(di, 1)));
    const auto two = hn::Set(di, 2);
    const auto next_x = hn::IfThenElse(hn::Eq(kz, two), hn::Zero(di), hn::Add(kz, hn::Set(di, 1)));
    const auto next_y = hn::IfThenElse(hn::Eq(next_x, two), hn::Zero(di), hn::Add(next_x, hn::Set(di, 1)));
    const auto dz = SelectAxis(d, di, kz, dir[0], dir[1], dir[2]);
    const auto flip = hn::RebindMask(di, hn::Lt(dz, zero));
    const auto kx = hn::IfThenElse(flip, next_y, next_x);
    const auto ky = hn::IfThenElse(flip, next_x, next_y);
    const hn::Vec<decltype(di)> k[3] = {kx, ky, kz};
    hn::Store(hn::Div(SelectAxis(d, di, kx, dir[0], dir[1], dir[2]), dz), d, b.s[0] + g);
    hn::Store(hn::Div(SelectAxis(d, di, ky, dir[0], dir[1], dir[2]), dz), d, b.s[1] + g);
    hn::Store(hn::Div(one, dz), d, b.s[2] + g);

    for (int a = 0; a < 3; ++a) {
      hn::Store(o[a], d, b.o[a] + g);
      const auto inv = hn::Div(one, dir[a]);
      hn::Store(inv, d, b.inv_d[a] + g);
      hn::Store(hn::Mul(inv, hn::Set(d, traverse_detail::kFarRound)), d, b.inv_d_far[a] + g);
      const auto neg = hn::RebindMask(du, hn::Lt(inv, zero));
      const auto lo = hn::Set(du, traverse_detail::bound_offset<N>(a, false));
      const auto hi = hn::Set(du, traverse_detail::bound_offset<N>(a, true));
      hn::Store(hn::IfThenElse(neg, hi, lo), du, b.near_off[a] + g);
      hn::Store(hn::IfThenElse(neg, lo, hi), du, b.far_off[a] + g);
      hn::Store(k[a], di, b.k[a] + g);
      hn::Store(SelectAxis(d, di, k[a], o[0], o[1], o[2]), d, b.ok[a] + g);
    }
    hn::Store(t_max, d, b.t_max + g);
  }
  b.valid = valid & ((1u << n) - 1);  // n <= 16
}

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_SINGLE_RAY_INL_H_TARGET
