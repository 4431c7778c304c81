// The light BVH's descent for many receivers (see light_bvh_batch.h): the Highway kernel and its dispatch entry
// point. Each lane does LightBvh::importance's and LightBvh::sample_bounded's operations in their order, with
// std::max / std::min spelled as the selects they are, so the results are the scalar code's bits (no contraction
// into fused multiply-adds, which baseline x86-64 does not have).
#include "core/no_fp_contract.h"  // first: see there
//
#include "light_bvh_batch.h"

#include <cstddef>
#include <cstdint>
#include <cstring>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "light_bvh_batch.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>                  // IWYU pragma: keep
#include <hwy/highway.h>

// Once, although foreach_target.h compiles this file once per target.
#ifndef TORTE_LIGHT_BVH_BATCH_DETAIL
#define TORTE_LIGHT_BVH_BATCH_DETAIL
namespace torte::light_bvh_batch_detail {
using Node = LightBvh::PackedNode;
// The node's fields as 32-bit words: the kernel gathers each field at node index * kStride + field.
enum Field : int32_t { kCx, kCy, kCz, kPhi, kWx, kWy, kWz, kCosO, kDiag2, kCosE, kIndex, kBits };
constexpr int32_t kStride = sizeof(Node) / 4;
static_assert(sizeof(Node) == 48 && kStride == 12, "the kernel's offsets assume LightBvh::PackedNode's layout");
static_assert(offsetof(Node, center) == 4 * kCx && offsetof(Node, phi) == 4 * kPhi && offsetof(Node, w) == 4 * kWx &&
              offsetof(Node, cos_o) == 4 * kCosO && offsetof(Node, diag2) == 4 * kDiag2 &&
              offsetof(Node, cos_e) == 4 * kCosE && offsetof(Node, index) == 4 * kIndex &&
              offsetof(Node, part_bits) == 4 * kBits);
}  // namespace torte::light_bvh_batch_detail
#endif

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using namespace light_bvh_batch_detail;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;
constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);

struct Receivers {
  VF px, py, pz, nx, ny, nz;
  MF has_n;
};

// std::max(a, b), std::min(a, b) and safe_sqrt as the scalar code evaluates them, NaN included.
HWY_INLINE VF StdMax(VF a, VF b) { return hn::IfThenElse(hn::Lt(a, b), b, a); }
HWY_INLINE VF StdMin(VF a, VF b) { return hn::IfThenElse(hn::Lt(b, a), b, a); }
HWY_INLINE VF SafeSqrt(VF v) { return hn::Sqrt(StdMax(v, hn::Zero(DF()))); }
// light_bvh.cc's cos_sub_clamped and sin_sub_clamped.
HWY_INLINE VF CosSub(VF sin_a, VF cos_a, VF sin_b, VF cos_b) {
  const VF rest = hn::Add(hn::Mul(cos_a, cos_b), hn::Mul(sin_a, sin_b));
  return hn::IfThenElse(hn::Gt(cos_a, cos_b), hn::Set(DF(), 1.0f), rest);
}
HWY_INLINE VF SinSub(VF sin_a, VF cos_a, VF sin_b, VF cos_b) {
  return hn::IfThenElse(hn::Gt(cos_a, cos_b), hn::Zero(DF()), hn::Sub(hn::Mul(sin_a, cos_b), hn::Mul(cos_a, sin_b)));
}
// dot(a, b) of vec.h: (a.x b.x + a.y b.y) + a.z b.z.
HWY_INLINE VF Dot(VF ax, VF ay, VF az, VF bx, VF by, VF bz) {
  return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}
HWY_INLINE VF Gather(const float* nodes, Field f, VI at) { return hn::GatherIndex(DF(), nodes + f, at); }

// LightBvh::importance(node, p, n) (min_d2 = 0) of the node whose first word is at word offset `at` in each lane.
// Both of the scalar code's paths are computed where lanes need them and the right one selected.
HWY_INLINE VF Importance(const float* nodes, const uint32_t* words, VI at, const Receivers& r) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const VF phi = Gather(nodes, kPhi, at), diag2 = Gather(nodes, kDiag2, at);
  const VF cos_o = Gather(nodes, kCosO, at), cos_e = Gather(nodes, kCosE, at);
  const VF dx = hn::Sub(r.px, Gather(nodes, kCx, at)), dy = hn::Sub(r.py, Gather(nodes, kCy, at)),
           dz = hn::Sub(r.pz, Gather(nodes, kCz, at));
  const VF dc2 = Dot(dx, dy, dz, dx, dy, dz);
  const VF d2 = StdMax(StdMax(dc2, hn::Mul(diag2, hn::Set(df, 1.0f / 64))), zero);
  const VF r2 = hn::Mul(diag2, hn::Set(df, 0.25f));
  const VF phi_d2 = hn::Div(phi, d2);
  const MF inside_sphere = hn::Le(dc2, r2);
  const MF everywhere = hn::And(hn::Le(cos_o, hn::Set(df, -1.0f)), hn::Lt(cos_e, one));

  // Normals everywhere: the receiver's cosine bound from the distance, the box's radius and |dot(p - c, n)|.
  const VF a = hn::Abs(Dot(dx, dy, dz, r.nx, r.ny, r.nz)), s_b = SafeSqrt(hn::Sub(dc2, r2));
  const VF s_i = SafeSqrt(hn::Sub(dc2, hn::Mul(a, a))), radius = hn::Mul(hn::Set(df, 0.5f), hn::Sqrt(diag2));
  const VF bounded = hn::Mul(phi_d2, hn::Div(StdMax(zero, hn::Add(hn::Mul(a, s_b), hn::Mul(s_i, radius))), dc2));
  const MF plain = hn::Or(hn::Or(hn::Not(r.has_n), inside_sphere), hn::Gt(a, s_b));
  VF value = hn::IfThenElse(plain, phi_d2, bounded);

  if (!hn::AllTrue(df, everywhere)) {  // the cone bound, where some lane's node has a cone of normals
    const VF len = hn::Sqrt(dc2);
    const VF wix = hn::Div(dx, len), wiy = hn::Div(dy, len), wiz = hn::Div(dz, len);
    VF cos_w = Dot(Gather(nodes, kWx, at), Gather(nodes, kWy, at), Gather(nodes, kWz, at), wix, wiy, wiz);
    const DU du;
    const VI bits = hn::BitCast(DI(), hn::GatherIndex(du, words + kBits, at));
    const MF two_sided =
        hn::RebindMask(df, hn::Ne(hn::And(bits, hn::Set(DI(), int32_t(Node::kTwoSided))), hn::Zero(DI())));
    cos_w = hn::IfThenElse(two_sided, hn::Abs(cos_w), cos_w);
    const VF sin_w = SafeSqrt(hn::Sub(one, hn::Mul(cos_w, cos_w)));
    const VF cos_b = hn::IfThenElse(inside_sphere, hn::Set(df, -1.0f), SafeSqrt(hn::Sub(one, hn::Div(r2, dc2))));
    const VF sin_b = SafeSqrt(hn::Sub(one, hn::Mul(cos_b, cos_b)));
    const VF sin_o = SafeSqrt(hn::Sub(one, hn::Mul(cos_o, cos_o)));
    const VF cos_x = CosSub(sin_w, cos_w, sin_o, cos_o), sin_x = SinSub(sin_w, cos_w, sin_o, cos_o);
    const VF cos_p = CosSub(sin_x, cos_x, sin_b, cos_b);
    VF cone = hn::Div(hn::Mul(phi, cos_p), d2);
    const VF cos_i = hn::Abs(Dot(wix, wiy, wiz, r.nx, r.ny, r.nz));
    const VF sin_i = SafeSqrt(hn::Sub(one, hn::Mul(cos_i, cos_i)));
    cone = hn::IfThenElse(r.has_n, hn::Mul(cone, CosSub(sin_i, cos_i, sin_b, cos_b)), cone);
    cone = hn::IfThenElse(hn::Le(cos_p, cos_e), zero, StdMax(cone, zero));
    value = hn::IfThenElse(everywhere, value, cone);
  }
  value = hn::IfThenElse(hn::Eq(d2, zero), phi, value);  // a point light at p itself
  return hn::IfThenElse(hn::Le(phi, zero), zero, value);
}

// One vector of receivers, from the root (an inner node) down: sample_bounded's steps in every lane at once.
// A lane that has reached its leaf (or found no light) keeps its result and descends from the root again, so
// that its gathers stay inside the tree, until every lane is done.
HWY_INLINE void DescendLanes(const Node* tree, const float* px, const float* py, const float* pz, const float* nx,
                             const float* ny, const float* nz, const float* u_in, const float* prob_in,
                             int32_t* light_out, float* pmf_out, uint32_t* part_out) {
  const DF df;
  const DI di;
  const DU du;
  const float* nodes = reinterpret_cast<const float*>(tree);
  const uint32_t* words = reinterpret_cast<const uint32_t*>(tree);
  Receivers r{hn::LoadU(df, px), hn::LoadU(df, py), hn::LoadU(df, pz), hn::LoadU(df, nx), hn::LoadU(df, ny),
              hn::LoadU(df, nz), {}};
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f), below_one = hn::Set(df, 0x1.fffffep-1f);
  r.has_n = hn::Or(hn::Or(hn::Ne(r.nx, zero), hn::Ne(r.ny, zero)), hn::Ne(r.nz, zero));
  VF u = hn::LoadU(df, u_in), prob = hn::LoadU(df, prob_in);
  VI node = hn::Zero(di);  // word offset of each lane's node: the root
  VI light = hn::Set(di, -1), part = hn::Zero(di);
  VF pmf = zero;
  MF active = hn::FirstN(df, hn::Lanes(df));
  const VI leaf_bit = hn::Set(di, int32_t(Node::kLeaf));
  const VI part_mask = hn::Set(di, int32_t(~(Node::kLeaf | Node::kTwoSided)));
  for (;;) {
    const VI first = hn::BitCast(di, hn::GatherIndex(du, words + kIndex, node));
    const VI at0 = hn::Add(hn::ShiftLeft<3>(first), hn::ShiftLeft<2>(first));  // first * kStride
    const VI at1 = hn::Add(at0, hn::Set(di, kStride));
    const VF i0 = Importance(nodes, words, at0, r), i1 = Importance(nodes, words, at1, r);
    const MF dead = hn::And(hn::Le(i0, zero), hn::Le(i1, zero));
    const VF p0 = hn::Div(i0, hn::Add(i0, i1));
    const MF left = hn::Lt(u, p0);
    // The chosen side's share: prob * p0 and u / p0 on the left, prob * (1 - p0) and (u - p0) / (1 - p0) on the
    // right, selected before the one multiply and one divide.
    const VF share = hn::IfThenElse(left, p0, hn::Sub(one, p0));
    prob = hn::Mul(prob, share);
    u = StdMin(hn::Div(hn::IfThenElse(left, u, hn::Sub(u, p0)), share), below_one);
    const VI next = hn::IfThenElse(hn::RebindMask(di, left), at0, at1);
    const VI bits = hn::BitCast(di, hn::GatherIndex(du, words + kBits, next));
    const MF leaf = hn::RebindMask(df, hn::Ne(hn::And(bits, leaf_bit), hn::Zero(di)));
    const MF done = hn::And(active, hn::AndNot(dead, leaf));
    const auto done_i = hn::RebindMask(di, done);
    light = hn::IfThenElse(done_i, hn::BitCast(di, hn::GatherIndex(du, words + kIndex, next)), light);
    part = hn::IfThenElse(done_i, hn::And(bits, part_mask), part);
    pmf = hn::IfThenElse(done, prob, pmf);
    active = hn::AndNot(hn::Or(dead, leaf), active);
    if (hn::AllFalse(df, active)) break;
    node = hn::IfThenElse(hn::RebindMask(di, active), next, hn::Zero(di));
  }
  hn::StoreU(light, di, light_out);
  hn::StoreU(pmf, df, pmf_out);
  hn::StoreU(hn::BitCast(du, part), du, part_out);
}

void Descend(const Node* tree, size_t count, const LightDescentInput& in, int32_t* light, float* pmf,
             uint32_t* part) {
  const size_t n = hn::Lanes(DF());
  size_t i = 0;
  for (; i + n <= count; i += n)
    DescendLanes(tree, in.px + i, in.py + i, in.pz + i, in.nx + i, in.ny + i, in.nz + i, in.u + i, in.prob + i,
                 light + i, pmf + i, part + i);
  if (i == count) return;
  // The remainder through padded local copies (Highway 1.0 has no LoadN/StoreN): receivers at the origin.
  const size_t rest = count - i;
  HWY_ALIGN float pad[8][kMaxLanes] = {};
  const float* from[8] = {in.px, in.py, in.pz, in.nx, in.ny, in.nz, in.u, in.prob};
  for (int f = 0; f < 8; ++f) std::memcpy(pad[f], from[f] + i, rest * sizeof(float));
  for (size_t k = rest; k < n; ++k) pad[7][k] = 1;
  HWY_ALIGN int32_t out_light[kMaxLanes];
  HWY_ALIGN float out_pmf[kMaxLanes];
  HWY_ALIGN uint32_t out_part[kMaxLanes];
  DescendLanes(tree, pad[0], pad[1], pad[2], pad[3], pad[4], pad[5], pad[6], pad[7], out_light, out_pmf, out_part);
  std::memcpy(light + i, out_light, rest * sizeof(int32_t));
  std::memcpy(pmf + i, out_pmf, rest * sizeof(float));
  std::memcpy(part + i, out_part, rest * sizeof(uint32_t));
}

int64_t LightBvhBatchTarget() { return HWY_TARGET; }

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

HWY_EXPORT(Descend);
HWY_EXPORT(LightBvhBatchTarget);

void light_bvh_descend(const LightBvh::PackedNode* nodes, size_t count, const LightDescentInput& in, int32_t* light,
                       float* pmf, uint32_t* part) {
  HWY_DYNAMIC_DISPATCH(Descend)(nodes, count, in, light, pmf, part);
}

const char* light_bvh_batch_target_name() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(LightBvhBatchTarget)()); }

}  // namespace torte
#endif  // HWY_ONCE
