// Parts shared by the single-ray (traverse.cc) and packet (traverse_packet.cc) traversal kernels: ray loading and
// validation (plain C++), and the vectorised watertight triangle test (per Highway target).
//
// Include after <hwy/highway.h> from a file compiled with floating-point contraction off (see traverse.cc): the
// edge functions must be evaluated as fl(fl(a*b) - fl(c*d)), exactly like geometry/triangle.cc, or the vector
// test would take different decisions than the scalar one and lose watertightness.

// ---- Plain C++ part (ordinary include guard) ----
#ifndef TORTE_SIMD_TRAVERSE_COMMON_H_
#define TORTE_SIMD_TRAVERSE_COMMON_H_
#include <cmath>
#include <cstdint>
#include <cstring>

#include "accel/hit.h"
#include "accel/wide_bvh.h"
#include "core/ray.h"

namespace torte::traverse_detail {

// Wide levels a traversal stack has room for; a ray pushes at most N - 1 entries per level.
constexpr int kMaxWideDepth = 64;
// Far slab distances are scaled up by this (pbrt's gamma(3), as SlabRay and Bounds3f::intersect do) so rays
// grazing a box never miss it through rounding.
constexpr float kFarRound = 1 + 2 * 3 * 0x1p-24f;

// The FMA slab test. A slab distance (b - o) / d computed as one fused multiply-add, fma(b, inv_d, -o * inv_d),
// takes two instructions fewer per node than (b - o) * inv_d, but o * inv_d is rounded: its error is relative to
// |o|, not to the distance, so the result is not bounded by a factor as SlabRay's is. The test stays conservative
// with a per-ray margin folded into the constant (o * inv_d + margin for entry planes, - margin for exit planes):
// with u = 2^-24, |b| <= extent (the tree's plane_extent) and r = inv_d, the four roundings (1 / d, o * r, the
// margin's addition, the fma) are off by at most u |r| (2.0002 |b| + 4.0002 |o|) + 2.0001 u margin in all, and
// margin = 8 u |r| (extent + |o|) covers that with a factor of two to spare. Unfused targets (SSE4, scalar) round
// b * r once more, u |r| |b|, still covered. kMinSlabMargin covers the absolute error of subnormal products.
// The cost: boxes a margin's width (a few 1e-7 of the scene's coordinates) beyond a ray are not culled.
constexpr float kSlabMargin = 8 * 0x1p-24f;
constexpr float kMinSlabMargin = 0x1p-120f;
// An axis takes the FMA test only where every product stays far from overflow (|r| (extent + |o|) < 2^100) and
// from 0 (|r| > 2^-100, so the empty slots' infinite planes give infinities, never 0 * inf): a zero or tiny
// direction component (axis-parallel rays) keeps the exact subtract-and-multiply test, whose NaN for a ray in a
// slab plane leaves that slab unconstrained.
constexpr float kMaxSlabScale = 0x1p100f;
constexpr float kMinInvDir = 0x1p-100f;
inline bool fma_slab_axis(float inv_d, float scale) {
  return scale < kMaxSlabScale && std::fabs(inv_d) > kMinInvDir;  // false for NaN
}

// Per axis, the largest |coordinate| of any child-bound plane in the tree: the root's children bound the rest.
template <int N>
inline void plane_extent(const WideBvh<N>& bvh, float extent[3]) {
  extent[0] = extent[1] = extent[2] = 0;
  if (bvh.nodes.empty()) return;
  const WideNode<N>& root = bvh.nodes[0];
  const float* lo[3] = {root.lo_x, root.lo_y, root.lo_z};
  const float* hi[3] = {root.hi_x, root.hi_y, root.hi_z};
  for (int i = 0; i < N; ++i) {
    if (root.child[i] == kEmptyChild) continue;
    for (int a = 0; a < 3; ++a)
      extent[a] = std::fmax(extent[a], std::fmax(std::fabs(lo[a][i]), std::fabs(hi[a][i])));
  }
}

// False for rays no triangle can be hit by, which every kernel reports as a miss: non-finite
// origin or direction components, a zero direction, or t_max NaN or <= 0.
inline bool is_valid_ray(const Ray& ray) {
  if (!is_finite(ray.o) || !is_finite(ray.d)) return false;
  if (ray.d.x == 0 && ray.d.y == 0 && ray.d.z == 0) return false;
  return ray.t_max > 0;  // false for NaN too
}

// Starts loading rays [at, at + 16) of all seven arrays when they exist (one cache line of each when aligned).
// The kernels call it a few blocks ahead: the arrays stream in from memory, and the hardware prefetcher alone left
// the packet set-up waiting on them (+1 to 2 % on a million camera rays, under 1 % on diffuse rays, AVX3, 2026-11-23).
constexpr size_t kRayPrefetchAhead = 64;  // rays
inline void prefetch_rays(const RaySoA& rays, size_t at, size_t count) {
  if (at + 16 > count) return;
  const float* arrays[7] = {rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz, rays.t_max};
  for (const float* a : arrays) __builtin_prefetch(a + at);
}

// The seven arrays of rays [begin, begin + n) for loads of P lanes: the caller's arrays when n == P, else copies
// in `tail` padded with zero rays (t_max = 0: invalid), so every P-lane load stays in bounds.
template <size_t P>
inline void ray_sources(const RaySoA& rays, size_t begin, size_t n, float (&tail)[7][P], const float* (&src)[7]) {
  const float* arrays[7] = {rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz, rays.t_max};
  for (int c = 0; c < 7; ++c) {
    src[c] = arrays[c] + begin;
    if (n == P) continue;
    for (size_t i = 0; i < P; ++i) tail[c][i] = i < n ? src[c][i] : 0.0f;
    src[c] = tail[c];
  }
}

// Offsets (in floats, from the start of a WideNode<N>) of the six child-bound arrays, which lie back to back.
template <int N>
constexpr uint32_t bound_offset(int axis, bool hi) {
  return uint32_t((hi ? 3 + axis : axis) * N);
}
static_assert(offsetof(WideNode<4>, hi_z) == 5 * 4 * sizeof(float));
static_assert(offsetof(WideNode<8>, hi_z) == 5 * 8 * sizeof(float));

// The first floats of a node, viewed as one array so near/far planes are picked by a per-ray offset.
template <int N>
inline const float* node_floats(const WideNode<N>& node) {
  return reinterpret_cast<const float*>(&node);
}

}  // namespace torte::traverse_detail
#endif  // TORTE_SIMD_TRAVERSE_COMMON_H_

// ---- Per-target part (Highway's include-once-per-target guard) ----
#if defined(TORTE_SIMD_TRAVERSE_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_TRAVERSE_INL_H_TARGET
#undef TORTE_SIMD_TRAVERSE_INL_H_TARGET
#else
#define TORTE_SIMD_TRAVERSE_INL_H_TARGET
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Mask as bits (lane i -> bit i); masks here have at most 16 lanes.
template <class D>
HWY_INLINE uint32_t MaskBits(D d, hn::Mask<D> m) {
  uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, m, bytes);
  uint32_t bits;
  std::memcpy(&bits, bytes, sizeof(bits));
  return bits;
}

// Selects per lane: m0 ? x : m1 ? y : z.
template <class M, class V>
HWY_INLINE V Pick(M m0, M m1, V x, V y, V z) {
  return hn::IfThenElse(m0, x, hn::IfThenElse(m1, y, z));
}

// Lanes holding a valid ray: traverse_detail::is_valid_ray, lane by lane.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> ValidRayLanes(D d, V ox, V oy, V oz, V dx, V dy, V dz, V t_max) {
  const V zero = hn::Zero(d);
  const auto finite = hn::And(hn::And(hn::And(hn::IsFinite(ox), hn::IsFinite(oy)), hn::IsFinite(oz)),
                              hn::And(hn::And(hn::IsFinite(dx), hn::IsFinite(dy)), hn::IsFinite(dz)));
  const auto zero_dir = hn::And(hn::And(hn::Eq(dx, zero), hn::Eq(dy, zero)), hn::Eq(dz, zero));
  return hn::AndNot(zero_dir, hn::And(finite, hn::Gt(t_max, zero)));
}

// WatertightRay's constructor lane by lane, with the same axis choice, tie rule and arithmetic, so the vector
// tests take the scalar test's decisions: kz = max_dimension(|d|) (x > y ? (x > z ? 0 : 2) : (y > z ? 1 : 2)),
// kx = kz + 1, ky = kx + 1 (mod 3), kx and ky swapped when d[kz] < 0. ix, iy, iz: 1 / dx, 1 / dy, 1 / dz (the
// same divisions WatertightRay does for sz).
template <class D>
struct WatertightSetup {
  hn::Mask<D> axis_is[3][2];  // axis_is[k][a]: the k-th permuted axis (kx, ky, kz) is a (a = 0, 1; neither: 2)
  hn::Vec<D> s[3];            // shear sx, sy, sz
};
template <class D, class V = hn::Vec<D>>
HWY_INLINE WatertightSetup<D> SetupWatertight(D d, V dx, V dy, V dz, V ix, V iy, V iz) {
  const V zero = hn::Zero(d);
  const auto ax = hn::Abs(dx), ay = hn::Abs(dy), az = hn::Abs(dz);
  const auto x_gt_y = hn::Gt(ax, ay);
  const auto kz0 = hn::And(x_gt_y, hn::Gt(ax, az)), kz1 = hn::AndNot(x_gt_y, hn::Gt(ay, az));
  const auto kz2 = hn::Not(hn::Or(kz0, kz1));
  const auto dkz = Pick(kz0, kz1, dx, dy, dz);
  const auto flip = hn::Lt(dkz, zero);
  WatertightSetup<D> w;
  w.axis_is[0][0] = hn::Or(hn::AndNot(flip, kz2), hn::And(flip, kz1));
  w.axis_is[0][1] = hn::Or(hn::AndNot(flip, kz0), hn::And(flip, kz2));
  w.axis_is[1][0] = hn::Or(hn::AndNot(flip, kz1), hn::And(flip, kz2));
  w.axis_is[1][1] = hn::Or(hn::AndNot(flip, kz2), hn::And(flip, kz0));
  w.axis_is[2][0] = kz0;
  w.axis_is[2][1] = kz1;
  w.s[2] = Pick(kz0, kz1, ix, iy, iz);
  w.s[0] = hn::Mul(Pick(w.axis_is[0][0], w.axis_is[0][1], dx, dy, dz), w.s[2]);
  w.s[1] = hn::Mul(Pick(w.axis_is[1][0], w.axis_is[1][1], dx, dy, dz), w.s[2]);
  return w;
}

template <class D>
struct WatertightLanes {
  hn::Mask<D> hit;   // inside and 0 < t < t_max by the range test; ResolveHits divides and checks again
  hn::Mask<D> zero;  // an edge function is exactly 0 and decides: the caller re-tests these with the scalar test
  hn::Vec<D> det, t_scaled, v, w;  // t = t_scaled / det, b1 = v / det, b2 = w / det
  hn::Vec<D> t, b1, b2;            // set by ResolveHits
};

// The watertight test of geometry/triangle.cc, lane by lane, operation for operation (same rounding, no FMA),
// so every lane takes the decision the scalar code takes. Inputs are the triangle's vertices minus the ray origin,
// already permuted to the ray's (kx, ky, kz) axes, and the ray's shear (sx, sy, sz). Only `candidates` lanes can
// hit or be reported as zero lanes. Stops before the division, which only ResolveHits does (callers may skip it
// when no lane of `hit` is set; calling it anyway is harmless, the lanes not hit are discarded).
// kSkipMisses: also return before the range test when no lane is inside (pays in any-hit packets, where most
// triangle tests miss; single rays test a leaf's triangles at once, and closest-hit packets after the interval's
// triangle culling, which leaves an even chance, lose more to the unpredictable branch).
template <bool kSkipMisses = false, class D, class V = hn::Vec<D>>
HWY_INLINE WatertightLanes<D> WatertightTest(D d, V akx, V aky, V akz, V bkx, V bky, V bkz, V ckx, V cky, V ckz,
                                             V sx, V sy, V sz, V t_max, hn::Mask<D> candidates) {
  using hn::Add;
  using hn::Mul;
  using hn::Sub;
  // Shear so the ray runs along +z through (0, 0).
  const V ax = Sub(akx, Mul(sx, akz)), ay = Sub(aky, Mul(sy, akz));
  const V bx = Sub(bkx, Mul(sx, bkz)), by = Sub(bky, Mul(sy, bkz));
  const V cx = Sub(ckx, Mul(sx, ckz)), cy = Sub(cky, Mul(sy, ckz));
  // Edge functions; Mul then Sub, never MulSub: a fused product breaks the antisymmetry between the two
  // triangles sharing an edge.
  const V u = Sub(Mul(cx, by), Mul(cy, bx));
  const V v = Sub(Mul(ax, cy), Mul(ay, cx));
  const V w = Sub(Mul(bx, ay), Mul(by, ax));
  const V zero = hn::Zero(d);
  const V det = Add(Add(u, v), w);
  WatertightLanes<D> r;
  r.det = det;
  r.v = v;
  r.w = w;
  // Inside: all three edge functions > 0 or all < 0; then det != 0 too (a sum of floats of one sign is never 0).
  // A float 0 may be a rounded non-zero, whose sign the scalar test finds in double: its zero lanes are those
  // where one edge function is 0 and the others do not already have mixed signs (those miss in double too: a
  // non-zero float edge function has the exact value's sign, as rounding is monotonic), i.e. min or max is 0.
  // A NaN edge function may hide from Min / Max (x86 returns the second operand), but it makes det and t_scaled
  // NaN, which the range test below rejects, and a zero lane re-tested by the scalar test rejects it there.
  const V lo = hn::Min(u, hn::Min(v, w)), hi = hn::Max(u, hn::Max(v, w));
  auto hit = hn::And(candidates, hn::Or(hn::Gt(lo, zero), hn::Lt(hi, zero)));
  r.zero = hn::And(candidates, hn::Or(hn::Eq(lo, zero), hn::Eq(hi, zero)));
  if (kSkipMisses && hn::AllFalse(d, hit)) {
    r.hit = hit;
    r.t_scaled = zero;
    return r;
  }
  const V az = Mul(sz, akz), bz = Mul(sz, bkz), cz = Mul(sz, ckz);
  r.t_scaled = Add(Add(Mul(u, az), Mul(v, bz)), Mul(w, cz));
  // 0 < t_scaled * sign(det) < t_max * |det| (false for NaN); the sign flip is exact.
  const V t_signed = hn::Xor(r.t_scaled, hn::And(det, hn::SignBit(d)));
  r.hit = hn::And(hit, hn::And(hn::Gt(t_signed, zero), hn::Lt(t_signed, Mul(t_max, hn::Abs(det)))));
  return r;
}

// The division for lanes that passed the range test: t, b1, b2, and the scalar test's final 0 < t < t_max.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void ResolveHits(D d, V t_max, WatertightLanes<D>& r) {
  const V inv_det = hn::Div(hn::Set(d, 1.0f), r.det);  // exact division, as 1.0f / det (no approximate reciprocal)
  r.t = hn::Mul(r.t_scaled, inv_det);
  r.hit = hn::And(r.hit, hn::And(hn::Gt(r.t, hn::Zero(d)), hn::Lt(r.t, t_max)));
  r.b1 = hn::Mul(r.v, inv_det);
  r.b2 = hn::Mul(r.w, inv_det);
}

}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target guard
