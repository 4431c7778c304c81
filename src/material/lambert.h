// Lambertian reflection. Two-sided like every opaque BSDF (see material/bsdf.h): it reflects on whichever side
// wo lies and never transmits.
#pragma once
#include "core/sampling.h"
#include "material/bsdf.h"

namespace torte {

struct LambertBsdf {
  Rgb albedo;

  bool has_non_specular() const { return true; }
  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi)) return {};
    return albedo * kInvPi;
  }
  float pdf(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi)) return 0;
    return cosine_hemisphere_pdf(std::fabs(wi.z));
  }
  // Cosine-weighted sampling of the hemisphere on wo's side.
  bool sample(Vec3f wo, float /*uc*/, Vec2f u, BsdfSample* s) const {
    Vec3f wi = sample_cosine_hemisphere(u);
    if (wo.z < 0) wi.z = -wi.z;
    s->pdf = cosine_hemisphere_pdf(std::fabs(wi.z));
    if (s->pdf <= 0) return false;
    s->wi = wi;
    s->f = albedo * kInvPi;
    s->flags = kBsdfReflection;
    s->eta = 1;
    return true;
  }
};

}  // namespace torte
