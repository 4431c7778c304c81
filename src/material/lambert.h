// Lambertian reflection (two-sided: the surface reflects on whichever side the light arrives, never transmits).
// Directions are in the local shading frame with the normal along +z on the side of wo.
#pragma once
#include "core/rgb.h"
#include "core/sampling.h"
#include "core/vec.h"

namespace torte {

struct LambertBsdf {
  Rgb albedo;

  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (wo.z * wi.z <= 0) return {};
    return albedo * kInvPi;
  }
  float pdf(Vec3f wo, Vec3f wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return cosine_hemisphere_pdf(std::fabs(wi.z));
  }
  struct Sample {
    Vec3f wi;
    Rgb weight;  // f * |cos| / pdf
    float pdf;
  };
  // Cosine-weighted sampling of the hemisphere on wo's side.
  bool sample(Vec3f wo, Vec2f u, Sample* s) const {
    Vec3f wi = sample_cosine_hemisphere(u);
    if (wo.z < 0) wi.z = -wi.z;
    s->pdf = cosine_hemisphere_pdf(std::fabs(wi.z));
    if (s->pdf <= 0) return false;
    s->wi = wi;
    s->weight = albedo;  // (albedo/pi) * cos / (cos/pi)
    return true;
  }
};

}  // namespace torte
