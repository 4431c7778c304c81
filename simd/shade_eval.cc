// Vectorised BSDF evaluation (see shade_eval.h): the Highway kernels and their dispatch entry points. Each
// kernel mirrors its scalar BSDF operation by operation (same order of floating-point operations, same branches
// turned into masks), so results agree to a few ulps.

// No contraction into FMA: the scalar BSDFs are compiled for baseline x86-64 (no FMA), so keep the same roundings.
#include "core/no_fp_contract.h"  // before every other include

#include "shade_eval.h"

#include <cstddef>
#include <cstdint>
#include <cstring>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "shade_eval.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>             // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using D = hn::ScalableTag<float>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

constexpr float kPiF = 3.14159265358979323846f;      // = kPi of core/vec.h
constexpr float kInvPiF = 0.31830988618379067154f;   // = kInvPi
constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);

struct EvalOut {
  V r, g, b, pdf;
};

// Runs `kernel` over [0, count): full vectors straight from the input arrays, the remainder through zero-padded
// local copies (Highway 1.0 has no LoadN/StoreN).
template <size_t kIn, class Kernel>
HWY_INLINE void Run(size_t count, const float* const* in, float* HWY_RESTRICT f_rgb, float* HWY_RESTRICT pdf,
                    const Kernel& kernel) {
  const D d;
  const size_t N = hn::Lanes(d);
  size_t i = 0;
  for (; i + N <= count; i += N) {
    const EvalOut o = kernel(d, in, i);
    hn::StoreInterleaved3(o.r, o.g, o.b, d, f_rgb + 3 * i);
    hn::StoreU(o.pdf, d, pdf + i);
  }
  if (i == count) return;
  const size_t rest = count - i;
  HWY_ALIGN float buf[kIn][kMaxLanes];
  const float* tail[kIn];
  for (size_t j = 0; j < kIn; ++j) {
    std::memset(buf[j], 0, sizeof(buf[j]));
    if (in[j]) std::memcpy(buf[j], in[j] + i, rest * sizeof(float));
    tail[j] = buf[j];
  }
  const EvalOut o = kernel(d, tail, 0);
  HWY_ALIGN float f_buf[3 * kMaxLanes];
  HWY_ALIGN float p_buf[kMaxLanes];
  hn::StoreInterleaved3(o.r, o.g, o.b, d, f_buf);
  hn::Store(o.pdf, d, p_buf);
  std::memcpy(f_rgb + 3 * i, f_buf, 3 * rest * sizeof(float));
  std::memcpy(pdf + i, p_buf, rest * sizeof(float));
}

// cosine_hemisphere_pdf(|wi.z|) of core/sampling.h: cos > 0 ? cos / pi : 0.
HWY_INLINE V CosinePdf(D d, V cos_abs) {
  return hn::IfThenElseZero(hn::Gt(cos_abs, hn::Zero(d)), hn::Mul(cos_abs, hn::Set(d, kInvPiF)));
}

// ---------------------------------------------------------------------------------------------------- Lambert
enum LambertIn { kLWoZ, kLWiZ, kLAr, kLAg, kLAb, kLambertInputs };
struct LambertKernel {
  HWY_INLINE EvalOut operator()(D d, const float* const* in, size_t i) const {
    const V wo_z = hn::LoadU(d, in[kLWoZ] + i), wi_z = hn::LoadU(d, in[kLWiZ] + i);
    const M same = hn::Gt(hn::Mul(wo_z, wi_z), hn::Zero(d));
    const V inv_pi = hn::Set(d, kInvPiF);
    EvalOut o;
    o.r = hn::IfThenElseZero(same, hn::Mul(hn::LoadU(d, in[kLAr] + i), inv_pi));
    o.g = hn::IfThenElseZero(same, hn::Mul(hn::LoadU(d, in[kLAg] + i), inv_pi));
    o.b = hn::IfThenElseZero(same, hn::Mul(hn::LoadU(d, in[kLAb] + i), inv_pi));
    o.pdf = hn::IfThenElseZero(same, CosinePdf(d, hn::Abs(wi_z)));
    return o;
  }
};

// ------------------------------------------------------------------------------------------------- Oren-Nayar
enum OrenNayarIn { kOWoX, kOWoY, kOWoZ, kOWiX, kOWiY, kOWiZ, kOAr, kOAg, kOAb, kOSigma, kOrenNayarInputs };
struct OrenNayarKernel {
  HWY_INLINE EvalOut operator()(D d, const float* const* in, size_t i) const {
    const V wo_x = hn::LoadU(d, in[kOWoX] + i), wo_y = hn::LoadU(d, in[kOWoY] + i);
    const V wo_z = hn::LoadU(d, in[kOWoZ] + i);
    const V wi_x = hn::LoadU(d, in[kOWiX] + i), wi_y = hn::LoadU(d, in[kOWiY] + i);
    const V wi_z = hn::LoadU(d, in[kOWiZ] + i);
    const V sigma = hn::LoadU(d, in[kOSigma] + i);
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    const M same = hn::Gt(hn::Mul(wo_z, wi_z), zero);

    const V s2 = hn::Mul(sigma, sigma);
    // a = 1 - s2 / (2 (s2 + 0.33)), b = 0.45 s2 / (s2 + 0.09)
    const V a = hn::Sub(one, hn::Div(s2, hn::Mul(hn::Set(d, 2.0f), hn::Add(s2, hn::Set(d, 0.33f)))));
    const V b = hn::Div(hn::Mul(hn::Set(d, 0.45f), s2), hn::Add(s2, hn::Set(d, 0.09f)));
    const V cos_o = hn::Abs(wo_z), cos_i = hn::Abs(wi_z);
    const V sin_o = hn::Sqrt(hn::Max(zero, hn::Sub(one, hn::Mul(cos_o, cos_o))));
    const V sin_i = hn::Sqrt(hn::Max(zero, hn::Sub(one, hn::Mul(cos_i, cos_i))));
    const V eps = hn::Set(d, 1e-4f);
    const M both = hn::And(hn::Gt(sin_i, eps), hn::Gt(sin_o, eps));
    const V dot_xy = hn::Add(hn::Mul(wi_x, wo_x), hn::Mul(wi_y, wo_y));
    const V cos_dphi = hn::IfThenElseZero(both, hn::Max(zero, hn::Div(dot_xy, hn::Mul(sin_i, sin_o))));
    const M i_higher = hn::Gt(cos_i, cos_o);
    const V sin_alpha = hn::IfThenElse(i_higher, sin_o, sin_i);
    const V tan_beta = hn::IfThenElse(i_higher, hn::Div(sin_i, cos_i), hn::Div(sin_o, cos_o));
    // albedo * (1/pi * (a + b * cos_dphi * sin_alpha * tan_beta))
    const V term = hn::Mul(hn::Mul(hn::Mul(b, cos_dphi), sin_alpha), tan_beta);
    const V scale = hn::IfThenElseZero(same, hn::Mul(hn::Set(d, kInvPiF), hn::Add(a, term)));
    EvalOut o;
    o.r = hn::Mul(hn::LoadU(d, in[kOAr] + i), scale);
    o.g = hn::Mul(hn::LoadU(d, in[kOAg] + i), scale);
    o.b = hn::Mul(hn::LoadU(d, in[kOAb] + i), scale);
    // Masked-out lanes: scale is 0 but albedo * 0 stays 0 for finite albedo; force exact zeros anyway.
    o.r = hn::IfThenElseZero(same, o.r);
    o.g = hn::IfThenElseZero(same, o.g);
    o.b = hn::IfThenElseZero(same, o.b);
    o.pdf = hn::IfThenElseZero(same, CosinePdf(d, cos_i));
    return o;
  }
};

// ---------------------------------------------------------------------------------------------- GGX conductor

// fresnel_complex of material/fresnel.h (the conductor Fresnel term in real arithmetic, pbrt-v3's FrConductor),
// operation by operation, for cos_i already min(|cos_i|, 1).
HWY_INLINE V FresnelConductor(D d, V cos_i, V eta, V k) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  const V cos2 = hn::Mul(cos_i, cos_i), sin2 = hn::Sub(one, cos2);
  const V eta2 = hn::Mul(eta, eta), k2 = hn::Mul(k, k);
  const V t0 = hn::Sub(hn::Sub(eta2, k2), sin2);
  const V a2_plus_b2 =
      hn::Sqrt(hn::Max(zero, hn::Add(hn::Mul(t0, t0), hn::Mul(hn::Mul(hn::Set(d, 4.0f), eta2), k2))));
  const V a = hn::Sqrt(hn::Max(zero, hn::Div(hn::Add(a2_plus_b2, t0), two)));
  const V t1 = hn::Add(a2_plus_b2, cos2), t2 = hn::Mul(hn::Mul(two, cos_i), a);
  const V rs = hn::Div(hn::Sub(t1, t2), hn::Add(t1, t2));
  const V t3 = hn::Add(hn::Mul(cos2, a2_plus_b2), hn::Mul(sin2, sin2)), t4 = hn::Mul(t2, sin2);
  const V rp = hn::Div(hn::Mul(rs, hn::Sub(t3, t4)), hn::Add(t3, t4));
  return hn::Div(hn::Add(rs, rp), two);
}

// GGX Lambda of material/microfacet.h: (sqrt(1 + alpha^2 tan^2) - 1) / 2, infinite when alpha^2 tan^2 is not
// finite (exactly grazing).
HWY_INLINE V LambdaGgx(D d, V ax, V ay, V wx, V wy, V wz) {
  const V z2 = hn::Mul(wz, wz);
  const V a2_tan2 = hn::Div(hn::Add(hn::Mul(hn::Mul(hn::Mul(ax, ax), wx), wx), hn::Mul(hn::Mul(hn::Mul(ay, ay), wy), wy)),
                            z2);
  const V inf = hn::Set(d, __builtin_huge_valf());
  const V one = hn::Set(d, 1.0f);
  const V lambda = hn::Div(hn::Sub(hn::Sqrt(hn::Add(one, a2_tan2)), one), hn::Set(d, 2.0f));
  return hn::IfThenElse(hn::Lt(a2_tan2, inf), lambda, inf);
}

enum ConductorIn {
  kCWoX, kCWoY, kCWoZ, kCWiX, kCWiY, kCWiZ, kCEr, kCEg, kCEb, kCKr, kCKg, kCKb, kCAx, kCAy, kConductorInputs
};
struct GgxConductorKernel {
  HWY_INLINE EvalOut operator()(D d, const float* const* in, size_t i) const {
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), four = hn::Set(d, 4.0f);
    const V wo_x = hn::LoadU(d, in[kCWoX] + i), wo_y = hn::LoadU(d, in[kCWoY] + i);
    const V wi_x = hn::LoadU(d, in[kCWiX] + i), wi_y = hn::LoadU(d, in[kCWiY] + i);
    const V wo_z_raw = hn::LoadU(d, in[kCWoZ] + i), wi_z_raw = hn::LoadU(d, in[kCWiZ] + i);
    const V ax = hn::LoadU(d, in[kCAx] + i), ay = hn::LoadU(d, in[kCAy] + i);
    // !same_hemisphere || effectively_smooth -> 0
    M valid = hn::Gt(hn::Mul(wo_z_raw, wi_z_raw), zero);
    valid = hn::AndNot(hn::Lt(hn::Max(ax, ay), hn::Set(d, 1e-3f)), valid);
    // upper(): mirror into the upper hemisphere
    const V wo_z = hn::Abs(wo_z_raw), wi_z = hn::Abs(wi_z_raw);
    const V h_x = hn::Add(wo_x, wi_x), h_y = hn::Add(wo_y, wi_y), h_z = hn::Add(wo_z, wi_z);
    const V len2 = hn::Add(hn::Add(hn::Mul(h_x, h_x), hn::Mul(h_y, h_y)), hn::Mul(h_z, h_z));
    valid = hn::And(valid, hn::Ne(len2, zero));
    const V len = hn::Sqrt(len2);
    const V wm_x = hn::Div(h_x, len), wm_y = hn::Div(h_y, len), wm_z = hn::Div(h_z, len);
    const V cos_om = hn::Add(hn::Add(hn::Mul(wo_x, wm_x), hn::Mul(wo_y, wm_y)), hn::Mul(wo_z, wm_z));

    // D(wm)
    const V x = hn::Div(wm_x, ax), y = hn::Div(wm_y, ay), z2 = hn::Mul(wm_z, wm_z);
    const V t = hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), z2);
    const V denom = hn::Mul(hn::Mul(hn::Mul(hn::Mul(hn::Set(d, kPiF), ax), ay), t), t);
    const V D_wm = hn::IfThenElseZero(hn::Gt(wm_z, zero), hn::Div(one, denom));
    // G(wo, wi), height-correlated
    const V lambda_o = LambdaGgx(d, ax, ay, wo_x, wo_y, wo_z);
    const V lambda_i = LambdaGgx(d, ax, ay, wi_x, wi_y, wi_z);
    const V G = hn::Div(one, hn::Add(hn::Add(one, lambda_o), lambda_i));
    // f = F * (D G / (4 cos_o cos_i))
    const V scale = hn::Div(hn::Mul(D_wm, G), hn::Mul(hn::Mul(four, wo_z), wi_z));
    const V cos_f = hn::Min(hn::Abs(cos_om), one);
    EvalOut o;
    o.r = hn::IfThenElseZero(
        valid, hn::Mul(FresnelConductor(d, cos_f, hn::LoadU(d, in[kCEr] + i), hn::LoadU(d, in[kCKr] + i)), scale));
    o.g = hn::IfThenElseZero(
        valid, hn::Mul(FresnelConductor(d, cos_f, hn::LoadU(d, in[kCEg] + i), hn::LoadU(d, in[kCKg] + i)), scale));
    o.b = hn::IfThenElseZero(
        valid, hn::Mul(FresnelConductor(d, cos_f, hn::LoadU(d, in[kCEb] + i), hn::LoadU(d, in[kCKb] + i)), scale));

    // pdf = D_wo(wm) / (4 wo.wm), D_wo(wm) = G1(wo) / |wo.z| * D(wm) * max(wo.wm, 0) (visible normals)
    const V G1 = hn::Div(one, hn::Add(one, lambda_o));
    const M facing = hn::And(hn::Gt(cos_om, zero), hn::Ne(wo_z, zero));
    const V dv = hn::IfThenElseZero(facing, hn::Mul(hn::Mul(hn::Div(G1, wo_z), D_wm), cos_om));
    o.pdf = hn::IfThenElseZero(valid, hn::Div(dv, hn::Mul(four, cos_om)));
    return o;
  }
};

}  // namespace

void EvalLambert(size_t count, const float* wo_z, const float* wi_z, const float* ar, const float* ag,
                 const float* ab, float* f_rgb, float* pdf) {
  const float* in[kLambertInputs] = {wo_z, wi_z, ar, ag, ab};
  Run<kLambertInputs>(count, in, f_rgb, pdf, LambertKernel());
}
void EvalOrenNayar(size_t count, const float* const* in, float* f_rgb, float* pdf) {
  Run<kOrenNayarInputs>(count, in, f_rgb, pdf, OrenNayarKernel());
}
void EvalGgxConductor(size_t count, const float* const* in, float* f_rgb, float* pdf) {
  Run<kConductorInputs>(count, in, f_rgb, pdf, GgxConductorKernel());
}
int64_t ShadeEvalTarget() { return HWY_TARGET; }

}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

HWY_EXPORT(EvalLambert);
HWY_EXPORT(EvalOrenNayar);
HWY_EXPORT(EvalGgxConductor);
HWY_EXPORT(ShadeEvalTarget);

void eval_lambert_soa(size_t count, const EvalDirsSoA& dirs, const float* albedo_r, const float* albedo_g,
                      const float* albedo_b, float* f_rgb, float* pdf) {
  HWY_DYNAMIC_DISPATCH(EvalLambert)(count, dirs.wo_z, dirs.wi_z, albedo_r, albedo_g, albedo_b, f_rgb, pdf);
}

void eval_oren_nayar_soa(size_t count, const EvalDirsSoA& dirs, const float* albedo_r, const float* albedo_g,
                         const float* albedo_b, const float* sigma, float* f_rgb, float* pdf) {
  const float* in[] = {dirs.wo_x, dirs.wo_y, dirs.wo_z, dirs.wi_x, dirs.wi_y, dirs.wi_z,
                       albedo_r,  albedo_g,  albedo_b,  sigma};
  HWY_DYNAMIC_DISPATCH(EvalOrenNayar)(count, in, f_rgb, pdf);
}

void eval_ggx_conductor_soa(size_t count, const EvalDirsSoA& dirs, const ConductorParamsSoA& p, float* f_rgb,
                            float* pdf) {
  const float* in[] = {dirs.wo_x, dirs.wo_y, dirs.wo_z, dirs.wi_x, dirs.wi_y, dirs.wi_z, p.eta_r,
                       p.eta_g,   p.eta_b,   p.k_r,     p.k_g,     p.k_b,     p.alpha_x, p.alpha_y};
  HWY_DYNAMIC_DISPATCH(EvalGgxConductor)(count, in, f_rgb, pdf);
}

const char* shade_eval_target_name() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(ShadeEvalTarget)()); }

}  // namespace torte
#endif  // HWY_ONCE
