// Refractive interfaces: DielectricBsdf (glass, water: a boundary between two media, smooth or rough) and
// ThinDielectricBsdf (a thin pane: both of its faces at once).
//
// eta is the relative index of refraction inside/outside; the inside is the side opposite the +z normal, so
// wo.z > 0 means the ray comes from outside. Tints scale the reflected and transmitted parts (1 is physical).
#pragma once
#include <cmath>

#include "material/bsdf.h"
#include "material/fresnel.h"
#include "material/microfacet.h"

namespace torte {

struct DielectricBsdf {
  float eta;
  MicrofacetDistribution distrib;
  TransportMode mode;
  Rgb reflect_tint, transmit_tint;

  DielectricBsdf(float eta_, MicrofacetDistribution d, TransportMode m, Rgb reflect = Rgb(1), Rgb transmit = Rgb(1))
      : eta(eta_), distrib(d), mode(m), reflect_tint(reflect), transmit_tint(transmit) {}

  // eta == 1 is an index-matched boundary: light passes straight through, whatever the roughness.
  bool is_specular() const { return eta == 1 || distrib.effectively_smooth(); }
  bool has_non_specular() const { return !is_specular(); }

  // Rough case: Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough Surfaces",
  // eq. 20 (reflection) and 21 (transmission), with the generalised half vector of eq. 16, in the form of
  // pbrt-v4 section 9.7.
  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (is_specular()) return {};
    Vec3f wm;
    float etap;
    if (!half_vector(wo, wi, &wm, &etap)) return {};
    const float cos_o = wo.z, cos_i = wi.z;
    if (etap == 1) {  // reflection
      // wo . wm = wi . wm exactly, but not once rounded; their mean is the same value whichever of wo and wi comes
      // first, so f stays reciprocal where the Fresnel term is steepest (at the critical angle, inside the medium,
      // one rounding moves it by 2e-4).
      const float f = fresnel_dielectric(0.5f * (dot(wo, wm) + dot(wi, wm)), eta);
      return reflect_tint * (distrib.D(wm) * distrib.G(wo, wi) * f / std::fabs(4 * cos_i * cos_o));
    }
    const float f = fresnel_dielectric(dot(wo, wm), eta);
    const float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap) * cos_i * cos_o;
    float ft = distrib.D(wm) * (1 - f) * distrib.G(wo, wi) * std::fabs(dot(wi, wm) * dot(wo, wm) / denom);
    // Radiance is compressed into the smaller solid angle on the dense side (pbrt-v4 section 9.5.2).
    if (mode == TransportMode::Radiance) ft /= sqr(etap);
    return transmit_tint * ft;
  }

  float pdf(Vec3f wo, Vec3f wi) const {
    if (is_specular()) return 0;
    Vec3f wm;
    float etap;
    if (!half_vector(wo, wi, &wm, &etap)) return 0;
    const float r = fresnel_dielectric(dot(wo, wm), eta), t = 1 - r;
    if (etap == 1) return distrib.pdf(wo, wm) / (4 * std::fabs(dot(wo, wm))) * r / (r + t);
    // Jacobian of the refraction map wm -> wi (Walter 2007, eq. 17).
    const float dwm_dwi = std::fabs(dot(wi, wm)) / sqr(dot(wi, wm) + dot(wo, wm) / etap);
    return distrib.pdf(wo, wm) * dwm_dwi * t / (r + t);
  }

  bool sample(Vec3f wo, float uc, Vec2f u, BsdfSample* s) const {
    if (wo.z == 0) return false;
    if (is_specular()) return sample_specular(wo, uc, s);
    const Vec3f wm = distrib.sample_wm(wo, u);
    const float cos_om = dot(wo, wm);
    if (cos_om * wo.z <= 0) return false;  // facet turned away from wo (Beckmann samples all normals)
    const float r = fresnel_dielectric(cos_om, eta), t = 1 - r;
    if (uc < r / (r + t)) {
      const Vec3f wi = reflect(wo, wm);
      if (!same_hemisphere(wo, wi)) return false;
      s->wi = wi;
      s->f = reflect_tint * (distrib.D(wm) * distrib.G(wo, wi) * r / std::fabs(4 * wi.z * wo.z));
      s->pdf = distrib.pdf(wo, wm) / (4 * std::fabs(cos_om)) * r / (r + t);
      s->flags = kBsdfReflection;
      s->eta = 1;
      return s->pdf > 0;
    }
    float etap;
    Vec3f wi;
    if (!refract(wo, wm, eta, &etap, &wi)) return false;  // cannot happen while t > 0; guards rounding
    if (same_hemisphere(wo, wi) || wi.z == 0) return false;
    const float cos_im = dot(wi, wm);
    const float denom = sqr(cos_im + cos_om / etap);
    float ft = distrib.D(wm) * t * distrib.G(wo, wi) * std::fabs(cos_im * cos_om / (wi.z * wo.z * denom));
    if (mode == TransportMode::Radiance) ft /= sqr(etap);
    s->wi = wi;
    s->f = transmit_tint * ft;
    s->pdf = distrib.pdf(wo, wm) * std::fabs(cos_im) / denom * t / (r + t);
    s->flags = kBsdfTransmission;
    s->eta = etap;
    return s->pdf > 0;
  }

 private:
  static float sqr(float x) { return x * x; }

  // Generalised half vector of (wo, wi) (Walter 2007 eq. 16), oriented to +z; *etap = 1 for reflection, else the
  // relative index crossed from wo's side. False for degenerate configurations and for microfacets that face away
  // from wo or wi (they cannot produce this scattering).
  bool half_vector(Vec3f wo, Vec3f wi, Vec3f* wm_out, float* etap) const {
    const float cos_o = wo.z, cos_i = wi.z;
    if (cos_o == 0 || cos_i == 0) return false;
    const bool reflection = cos_o * cos_i > 0;
    *etap = reflection ? 1 : (cos_o > 0 ? eta : 1 / eta);
    Vec3f wm = wi * *etap + wo;
    if (length_squared(wm) == 0) return false;
    wm = normalize(wm);
    if (wm.z < 0) wm = -wm;
    if (dot(wm, wi) * cos_i <= 0 || dot(wm, wo) * cos_o <= 0) return false;
    *wm_out = wm;
    return true;
  }

  // Smooth interface: reflect with probability R, refract with probability T = 1 - R (Fresnel, pbrt-v4 9.5).
  bool sample_specular(Vec3f wo, float uc, BsdfSample* s) const {
    const float r = fresnel_dielectric(wo.z, eta), t = 1 - r;
    if (uc < r / (r + t)) {
      s->wi = Vec3f(-wo.x, -wo.y, wo.z);
      s->f = reflect_tint * (r / std::fabs(wo.z));
      s->pdf = r / (r + t);
      s->flags = kBsdfReflection | kBsdfSpecular;
      s->eta = 1;
      return true;
    }
    Vec3f wi;
    float etap = 1;
    if (eta == 1) {
      wi = -wo;
    } else if (!refract(wo, Vec3f(0, 0, 1), eta, &etap, &wi)) {
      return false;  // total internal reflection has t = 0, so this is only reached through rounding
    }
    if (wi.z == 0) return false;
    float ft = t / std::fabs(wi.z);
    if (mode == TransportMode::Radiance) ft /= sqr(etap);
    s->wi = wi;
    s->f = transmit_tint * ft;
    s->pdf = t / (r + t);
    s->flags = kBsdfTransmission | kBsdfSpecular;
    s->eta = etap;
    return true;
  }
};

// A thin dielectric slab (window pane, soap film, leaf without volume): light reflects off either face or is
// transmitted after inter-reflections inside; the two refractions cancel, so transmission goes straight through
// (wi = -wo) with no change of medium and no radiance scaling. Summing the geometric series of internal bounces
// (pbrt-v4 section 9.5.3): R' = R + T^2 R / (1 - R^2), T' = 1 - R'. Both lobes are deltas.
struct ThinDielectricBsdf {
  float eta;
  Rgb reflect_tint{1}, transmit_tint{1};

  ThinDielectricBsdf(float eta_, Rgb reflect = Rgb(1), Rgb transmit = Rgb(1))
      : eta(eta_), reflect_tint(reflect), transmit_tint(transmit) {}

  Rgb eval(Vec3f, Vec3f) const { return {}; }
  float pdf(Vec3f, Vec3f) const { return 0; }
  bool has_non_specular() const { return false; }

  // Slab reflectance R' for a ray at |cos| = cos_theta.
  float reflectance(float cos_theta) const {
    float r = fresnel_dielectric(std::fabs(cos_theta), eta);
    if (r < 1) r += (1 - r) * (1 - r) * r / (1 - r * r);
    return r;
  }

  bool sample(Vec3f wo, float uc, Vec2f /*u*/, BsdfSample* s) const {
    if (wo.z == 0) return false;
    const float r = reflectance(wo.z), t = 1 - r;
    if (uc < r / (r + t)) {
      s->wi = Vec3f(-wo.x, -wo.y, wo.z);
      s->f = reflect_tint * (r / std::fabs(wo.z));
      s->pdf = r / (r + t);
      s->flags = kBsdfReflection | kBsdfSpecular;
    } else {
      s->wi = -wo;
      s->f = transmit_tint * (t / std::fabs(wo.z));
      s->pdf = t / (r + t);
      s->flags = kBsdfTransmission | kBsdfSpecular;
    }
    s->eta = 1;
    return true;
  }
};

}  // namespace torte
