// "Plastic": a Lambertian base of the given albedo under a dielectric coating of relative index eta, smooth or
// rough. Two-sided (opaque).
//
// Model: Mitsuba's plastic / roughplastic (Jakob 2010, after Weidlich & Wilkie 2007), which accounts for the
// light that bounces between base and coating:
//   f_diffuse = albedo (1 - F(cos_o)) (1 - F(cos_i)) / (pi eta^2 (1 - albedo Fdr_int)),
// where F is the dielectric Fresnel reflectance at the macro normal and Fdr_int the hemispherical Fresnel
// reflectance seen from inside the coating. Energy balance at albedo a: of the light arriving from wi, 1 - F(cos_i)
// enters; the base reflects a of it; a fraction 1 - Fdr_int escapes and Fdr_int returns to the base, so the
// escaping total is the geometric series a (1 - Fdr_int) sum_k (a Fdr_int)^k = a (1 - Fdr_int) / (1 - a Fdr_int),
// which is <= 1. The escaping radiance has the angular shape (1 - F(cos_o)) / eta^2, and since
// integral (1 - F(cos_o)) cos_o dwo / (pi eta^2) = 1 - Fdr_int, the diffuse albedo from wi is exactly
// (1 - F(cos_i)) a (1 - Fdr_int) / (1 - a Fdr_int) <= 1 - F(cos_i).
//
// Specular coat: smooth -> a delta reflection with weight F(cos_o). Rough -> Torrance-Sparrow with the Fresnel
// factor F(max(wo.wm, cos_o, cos_i)). Taking the largest cosine (F decreases with cos) instead of Mitsuba's
// F(wo.wm) is our change: it bounds the factor by both F(cos_o) and F(cos_i), so the specular albedo from any
// direction is at most F(cos) times the masking term's integral (<= 1), and specular plus diffuse albedo can
// never exceed 1 - without Mitsuba's precomputed rough-transmittance tables. It stays reciprocal (symmetric in wo,
// wi) and equals F(cos) in the smooth limit (wm = n). The price is energy: with plain F(wo.wm) the albedo-1
// furnace exceeds 1 slightly (1.0005 at GGX alpha 0.05, cos 0.7), with the clamp it stays below, but at grazing
// angles rough coats lose more light (albedo at wo.z = 0.1, eta 1.5, GGX alpha 0.05: 0.79 vs 0.86 unclamped;
// alpha 0.3: 0.53 vs 0.58). Most of that loss is common to both: single-scattering masking, and a base lit
// through the macro-normal transmittance 1 - F(cos), which is small at grazing.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "material/bsdf.h"
#include "material/fresnel.h"
#include "material/microfacet.h"

namespace torte {

struct CoatedDiffuseBsdf {
  Rgb albedo;
  float eta;  // coating index over the outside medium's
  MicrofacetDistribution distrib;
  float fdr_int;  // hemispherical reflectance of the coating seen from inside

  CoatedDiffuseBsdf(Rgb albedo_, float eta_, MicrofacetDistribution d)
      : albedo(albedo_), eta(eta_), distrib(d), fdr_int(fresnel_diffuse_reflectance(1 / eta_)) {}

  bool smooth() const { return distrib.effectively_smooth(); }
  bool has_non_specular() const { return true; }

  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi)) return {};
    wo = upper(wo);
    wi = upper(wi);
    Rgb f = diffuse(wo.z, wi.z);
    if (!smooth()) f += Rgb(specular(wo, wi));
    return f;
  }

  float pdf(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi)) return 0;
    wo = upper(wo);
    wi = upper(wi);
    const float ps = specular_probability(wo.z);
    float p = (1 - ps) * cosine_hemisphere_pdf(wi.z);
    if (!smooth()) p += ps * specular_pdf(wo, wi);
    return p;
  }

  bool sample(Vec3f wo, float uc, Vec2f u, BsdfSample* s) const {
    if (wo.z == 0) return false;
    const float side = wo.z < 0 ? -1.0f : 1.0f;
    const Vec3f wo_up = upper(wo);
    const float ps = specular_probability(wo_up.z);
    Vec3f wi;
    if (uc < ps) {
      if (smooth()) {
        s->wi = Vec3f(-wo.x, -wo.y, wo.z);
        s->f = Rgb(fresnel_dielectric(wo_up.z, eta) / wo_up.z);
        s->pdf = ps;
        s->flags = kBsdfReflection | kBsdfSpecular;
        s->eta = 1;
        return true;
      }
      const Vec3f wm = distrib.sample_wm(wo_up, u);
      if (dot(wo_up, wm) <= 0) return false;
      wi = reflect(wo_up, wm);
      if (wi.z <= 0) return false;
    } else {
      wi = sample_cosine_hemisphere(u);
      if (wi.z <= 0) return false;
    }
    // Either lobe can produce any non-delta direction: the value and pdf are those of the whole mixture.
    Rgb f = diffuse(wo_up.z, wi.z);
    float p = (1 - ps) * cosine_hemisphere_pdf(wi.z);
    if (!smooth()) {
      f += Rgb(specular(wo_up, wi));
      p += ps * specular_pdf(wo_up, wi);
    }
    if (!(p > 0)) return false;
    wi.z *= side;
    s->wi = wi;
    s->f = f;
    s->pdf = p;
    s->flags = kBsdfReflection;
    s->eta = 1;
    return true;
  }

  // Probability of sampling the coating's reflection rather than the base: its Fresnel weight against what the
  // base can return, so dark bases spend their samples on highlights.
  float specular_probability(float cos_o) const {
    const float fs = fresnel_dielectric(cos_o, eta);
    const float fd = (1 - fs) * std::clamp(albedo.average(), 0.0f, 1.0f);
    return fs + fd > 0 ? fs / (fs + fd) : 0.5f;
  }

 private:
  static Vec3f upper(Vec3f w) { return {w.x, w.y, std::fabs(w.z)}; }

  // Arguments in the upper hemisphere from here on.
  Rgb diffuse(float cos_o, float cos_i) const {
    const float transmit = (1 - fresnel_dielectric(cos_o, eta)) * (1 - fresnel_dielectric(cos_i, eta));
    const Rgb denom = Rgb(1) - albedo * fdr_int;
    return Rgb(albedo.r / denom.r, albedo.g / denom.g, albedo.b / denom.b) * (transmit * kInvPi / (eta * eta));
  }
  float specular(Vec3f wo, Vec3f wi) const {
    const Vec3f h = wo + wi;
    if (wo.z <= 0 || wi.z <= 0 || length_squared(h) == 0) return 0;
    const Vec3f wm = normalize(h);
    const float f = fresnel_dielectric(std::max({dot(wo, wm), wo.z, wi.z}), eta);
    return distrib.D(wm) * distrib.G(wo, wi) * f / (4 * wo.z * wi.z);
  }
  float specular_pdf(Vec3f wo, Vec3f wi) const {
    const Vec3f h = wo + wi;
    if (wo.z <= 0 || wi.z <= 0 || length_squared(h) == 0) return 0;
    const Vec3f wm = normalize(h);
    return distrib.pdf(wo, wm) / (4 * dot(wo, wm));
  }
};

}  // namespace torte
