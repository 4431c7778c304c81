// MaterialTraits<T>: everything generic code needs to know about shaded material type T — its parameter table,
// how to build its BSDF at a hit (evaluate the parameters, constants or textures, and construct the BSDF value
// type), and two facts the shading kernel uses. One specialisation per type of ShadedMaterialTypes
// (material/material_types.h); the kernels are templated on the type, so every call inlines and no hit pays a
// virtual call.
//   Bsdf                     the BSDF value type
//   params(tables)           the type's row array in MaterialTables
//   bsdf(tables, textures, row, tc, mode)
//   kSingleLobe              sample() ignores its lobe number (the kernel then draws no sampler dimension for it)
//   kBatchEval               the renderer's phase 2 uses the SIMD kernel eval_batch_simd (render/shade_eval_batch.h)
#pragma once
#include "material/coated_diffuse.h"
#include "material/conductor.h"
#include "material/dielectric.h"
#include "material/lambert.h"
#include "material/mirror.h"
#include "material/oren_nayar.h"
#include "material/material_types.h"
#include "texture/texture.h"

namespace torte {

template <MaterialType T>
struct MaterialTraits;

namespace detail {
inline MicrofacetDistribution distribution(const TextureTable& tex, const RoughnessParams& r,
                                           const TextureContext& tc) {
  // Textures may produce any value: keep alpha in the range the distributions handle.
  float ax = std::clamp(tex.eval(r.u, tc), 0.0f, 2.0f);
  float ay = std::clamp(tex.eval(r.v, tc), 0.0f, 2.0f);
  if (r.remap) {
    ax *= ax;
    ay *= ay;
  }
  return MicrofacetDistribution(r.distribution, ax, ay);
}
inline Rgb clamp01(Rgb c) {
  return {std::clamp(c.r, 0.0f, 1.0f), std::clamp(c.g, 0.0f, 1.0f), std::clamp(c.b, 0.0f, 1.0f)};
}
inline Rgb clamp0(Rgb c) { return {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)}; }
// IOR from a texture: non-positive values would make Fresnel meaningless.
inline float positive_eta(float eta) { return eta > 1e-3f ? eta : 1e-3f; }
}  // namespace detail

template <>
struct MaterialTraits<MaterialType::Lambert> {
  using Bsdf = LambertBsdf;
  static auto& params(auto& tables) { return tables.lambert; }  // MaterialTables, const or not
  static constexpr bool kSingleLobe = true, kBatchEval = false;  // SIMD phase 2 does not pay for Lambert
  static Bsdf bsdf(const MaterialTables& m, const TextureTable& tex, uint32_t i, const TextureContext& tc,
                   TransportMode) {
    return {detail::clamp01(tex.eval(m.lambert[i].albedo, tc))};
  }
};

template <>
struct MaterialTraits<MaterialType::OrenNayar> {
  using Bsdf = OrenNayarBsdf;
  static auto& params(auto& tables) { return tables.oren_nayar; }  // MaterialTables, const or not
  static Bsdf bsdf(const MaterialTables& m, const TextureTable& tex, uint32_t i, const TextureContext& tc,
                   TransportMode) {
    const OrenNayarParams& p = m.oren_nayar[i];
    const float sigma_degrees = std::clamp(tex.eval(p.sigma, tc), 0.0f, 90.0f);
    return Bsdf{detail::clamp01(tex.eval(p.albedo, tc)), sigma_degrees * (kPi / 180)};
  }
  static constexpr bool kSingleLobe = true, kBatchEval = true;  // SIMD phase 2: about 1.3x (shade_eval_batch.h)
};

template <>
struct MaterialTraits<MaterialType::Mirror> {
  using Bsdf = MirrorBsdf;
  static auto& params(auto& tables) { return tables.mirror; }  // MaterialTables, const or not
  static constexpr bool kSingleLobe = false, kBatchEval = false;
  static Bsdf bsdf(const MaterialTables& m, const TextureTable& tex, uint32_t i, const TextureContext& tc,
                   TransportMode) {
    return Bsdf{detail::clamp01(tex.eval(m.mirror[i].tint, tc))};
  }
};

template <>
struct MaterialTraits<MaterialType::Conductor> {
  using Bsdf = ConductorBsdf;
  static auto& params(auto& tables) { return tables.conductor; }  // MaterialTables, const or not
  static Bsdf bsdf(const MaterialTables& m, const TextureTable& tex, uint32_t i, const TextureContext& tc,
                   TransportMode) {
    const ConductorParams& p = m.conductor[i];
    return Bsdf(detail::clamp0(tex.eval(p.eta, tc)), detail::clamp0(tex.eval(p.k, tc)),
                detail::distribution(tex, p.roughness, tc));
  }
  // SIMD phase 2 (about 3x, shade_eval_batch.h); Beckmann candidates use the scalar BSDF inside the batch.
  static constexpr bool kSingleLobe = false, kBatchEval = true;
};

template <>
struct MaterialTraits<MaterialType::Dielectric> {
  using Bsdf = DielectricBsdf;
  static auto& params(auto& tables) { return tables.dielectric; }  // MaterialTables, const or not
  static constexpr bool kSingleLobe = false, kBatchEval = false;
  static Bsdf bsdf(const MaterialTables& m, const TextureTable& tex, uint32_t i, const TextureContext& tc,
                   TransportMode mode) {
    const DielectricParams& p = m.dielectric[i];
    return Bsdf(detail::positive_eta(tex.eval(p.eta, tc)), detail::distribution(tex, p.roughness, tc),
                mode, detail::clamp01(tex.eval(p.reflect_tint, tc)),
                detail::clamp01(tex.eval(p.transmit_tint, tc)));
  }
};

template <>
struct MaterialTraits<MaterialType::ThinDielectric> {
  using Bsdf = ThinDielectricBsdf;
  static auto& params(auto& tables) { return tables.thin_dielectric; }  // MaterialTables, const or not
  static constexpr bool kSingleLobe = false, kBatchEval = false;
  static Bsdf bsdf(const MaterialTables& m, const TextureTable& tex, uint32_t i, const TextureContext& tc,
                   TransportMode) {
    const ThinDielectricParams& p = m.thin_dielectric[i];
    return Bsdf(detail::positive_eta(tex.eval(p.eta, tc)), detail::clamp01(tex.eval(p.reflect_tint, tc)),
                detail::clamp01(tex.eval(p.transmit_tint, tc)));
  }
};

template <>
struct MaterialTraits<MaterialType::CoatedDiffuse> {
  using Bsdf = CoatedDiffuseBsdf;
  static auto& params(auto& tables) { return tables.coated_diffuse; }  // MaterialTables, const or not
  static constexpr bool kSingleLobe = false, kBatchEval = false;
  static Bsdf bsdf(const MaterialTables& m, const TextureTable& tex, uint32_t i, const TextureContext& tc,
                   TransportMode) {
    const CoatedDiffuseParams& p = m.coated_diffuse[i];
    return Bsdf(detail::clamp01(tex.eval(p.albedo, tc)), detail::positive_eta(tex.eval(p.eta, tc)),
                detail::distribution(tex, p.roughness, tc));
  }
};

}  // namespace torte
