// MaterialTraits<T>: how the shading kernel of material type T builds its BSDF at a hit — evaluate the type's
// parameters (constants or textures) and construct the BSDF value type. One specialisation per shaded type; the
// kernel in render/shade.h is templated on the type, so every call below inlines and no hit pays a virtual call.
#pragma once
#include "material/coated_diffuse.h"
#include "material/conductor.h"
#include "material/dielectric.h"
#include "material/lambert.h"
#include "material/mirror.h"
#include "material/oren_nayar.h"
#include "render/shade_eval_batch.h"
#include "scene/scene.h"

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
  static Bsdf bsdf(const Scene& s, uint32_t i, const TextureContext& tc, TransportMode) {
    return {detail::clamp01(s.textures.eval(s.materials.lambert[i].albedo, tc))};
  }
};

template <>
struct MaterialTraits<MaterialType::OrenNayar> {
  using Bsdf = OrenNayarBsdf;
  static Bsdf bsdf(const Scene& s, uint32_t i, const TextureContext& tc, TransportMode) {
    const OrenNayarParams& p = s.materials.oren_nayar[i];
    const float sigma_degrees = std::clamp(s.textures.eval(p.sigma, tc), 0.0f, 90.0f);
    return Bsdf{detail::clamp01(s.textures.eval(p.albedo, tc)), sigma_degrees * (kPi / 180)};
  }
  // Phase 2 of shade_queue with the SIMD kernel of simd/shade_eval.h (render/shade_eval_batch.cc).
  static void eval_batch(ShadeScratch<Bsdf>& sc);
};

template <>
struct MaterialTraits<MaterialType::Mirror> {
  using Bsdf = MirrorBsdf;
  static Bsdf bsdf(const Scene& s, uint32_t i, const TextureContext& tc, TransportMode) {
    return Bsdf{detail::clamp01(s.textures.eval(s.materials.mirror[i].tint, tc))};
  }
};

template <>
struct MaterialTraits<MaterialType::Conductor> {
  using Bsdf = ConductorBsdf;
  static Bsdf bsdf(const Scene& s, uint32_t i, const TextureContext& tc, TransportMode) {
    const ConductorParams& p = s.materials.conductor[i];
    return Bsdf(detail::clamp0(s.textures.eval(p.eta, tc)), detail::clamp0(s.textures.eval(p.k, tc)),
                detail::distribution(s.textures, p.roughness, tc));
  }
  // Phase 2 of shade_queue with the SIMD kernel of simd/shade_eval.h (render/shade_eval_batch.cc); Beckmann
  // candidates use the scalar BSDF.
  static void eval_batch(ShadeScratch<Bsdf>& sc);
};

template <>
struct MaterialTraits<MaterialType::Dielectric> {
  using Bsdf = DielectricBsdf;
  static Bsdf bsdf(const Scene& s, uint32_t i, const TextureContext& tc, TransportMode mode) {
    const DielectricParams& p = s.materials.dielectric[i];
    return Bsdf(detail::positive_eta(s.textures.eval(p.eta, tc)), detail::distribution(s.textures, p.roughness, tc),
                mode, detail::clamp01(s.textures.eval(p.reflect_tint, tc)),
                detail::clamp01(s.textures.eval(p.transmit_tint, tc)));
  }
};

template <>
struct MaterialTraits<MaterialType::ThinDielectric> {
  using Bsdf = ThinDielectricBsdf;
  static Bsdf bsdf(const Scene& s, uint32_t i, const TextureContext& tc, TransportMode) {
    const ThinDielectricParams& p = s.materials.thin_dielectric[i];
    return Bsdf(detail::positive_eta(s.textures.eval(p.eta, tc)), detail::clamp01(s.textures.eval(p.reflect_tint, tc)),
                detail::clamp01(s.textures.eval(p.transmit_tint, tc)));
  }
};

template <>
struct MaterialTraits<MaterialType::CoatedDiffuse> {
  using Bsdf = CoatedDiffuseBsdf;
  static Bsdf bsdf(const Scene& s, uint32_t i, const TextureContext& tc, TransportMode) {
    const CoatedDiffuseParams& p = s.materials.coated_diffuse[i];
    return Bsdf(detail::clamp01(s.textures.eval(p.albedo, tc)), detail::positive_eta(s.textures.eval(p.eta, tc)),
                detail::distribution(s.textures, p.roughness, tc));
  }
};

}  // namespace torte
