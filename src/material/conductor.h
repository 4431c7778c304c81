// Metal: Torrance-Sparrow microfacet reflection with the exact conductor Fresnel term (pbrt-v4 section 9.6),
// f = D(wm) F(wo.wm) G(wo, wi) / (4 cos_o cos_i), sampled through the distribution of visible normals. When the
// distribution is effectively smooth it degenerates to a delta reflection. Two-sided: a ray from the back sees
// the mirror image of the same surface.
#pragma once
#include <cmath>

#include "material/bsdf.h"
#include "material/fresnel.h"
#include "material/microfacet.h"

namespace torte {

struct ConductorBsdf {
  Rgb eta, k;  // complex index of refraction eta + i k relative to the outside medium
  MicrofacetDistribution distrib;

  ConductorBsdf(Rgb eta_, Rgb k_, MicrofacetDistribution d) : eta(eta_), k(k_), distrib(d) {}

  bool has_non_specular() const { return !distrib.effectively_smooth(); }

  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi) || distrib.effectively_smooth()) return {};
    wo = upper(wo);
    wi = upper(wi);
    const Vec3f h = wo + wi;
    if (length_squared(h) == 0) return {};
    const Vec3f wm = normalize(h);
    const Rgb f = fresnel_conductor(dot(wo, wm), eta, k);
    return f * (distrib.D(wm) * distrib.G(wo, wi) / (4 * wo.z * wi.z));
  }

  float pdf(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi) || distrib.effectively_smooth()) return 0;
    wo = upper(wo);
    wi = upper(wi);
    const Vec3f h = wo + wi;
    if (length_squared(h) == 0) return 0;
    const Vec3f wm = normalize(h);
    // Change of variables from wm to wi = reflect(wo, wm): dwm/dwi = 1 / (4 wo.wm).
    return distrib.pdf(wo, wm) / (4 * dot(wo, wm));
  }

  bool sample(Vec3f wo, float /*uc*/, Vec2f u, BsdfSample* s) const {
    if (wo.z == 0) return false;
    if (distrib.effectively_smooth()) {
      s->wi = Vec3f(-wo.x, -wo.y, wo.z);
      s->f = fresnel_conductor(wo.z, eta, k) / std::fabs(wo.z);
      s->pdf = 1;
      s->flags = kBsdfReflection | kBsdfSpecular;
      s->eta = 1;
      return true;
    }
    const float side = wo.z < 0 ? -1.0f : 1.0f;
    const Vec3f wo_up = upper(wo);
    const Vec3f wm = distrib.sample_wm(wo_up, u);
    const float cos_om = dot(wo_up, wm);
    if (cos_om <= 0) return false;  // only possible with Beckmann, which does not sample visible normals
    Vec3f wi = reflect(wo_up, wm);
    if (wi.z <= 0) return false;  // reflected below the macro surface: shadowed, no contribution
    s->f = fresnel_conductor(cos_om, eta, k) * (distrib.D(wm) * distrib.G(wo_up, wi) / (4 * wo_up.z * wi.z));
    s->pdf = distrib.pdf(wo_up, wm) / (4 * cos_om);
    wi.z *= side;
    s->wi = wi;
    s->flags = kBsdfReflection;
    s->eta = 1;
    return s->pdf > 0;
  }

 private:
  // Mirrors a direction into the upper hemisphere, so the back side reflects like the front.
  static Vec3f upper(Vec3f w) { return {w.x, w.y, std::fabs(w.z)}; }
};

}  // namespace torte
