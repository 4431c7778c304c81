// Oren-Nayar rough diffuse reflection, the "qualitative" model of Oren & Nayar 1994 (eq. 30) as given in pbrt-v3
// section 8.4.2: f = albedo/pi (A + B max(0, cos(phi_i - phi_o)) sin(alpha) tan(beta)), alpha = max(theta_i,
// theta_o), beta = min. sigma is the standard deviation of the facet slope angle, in radians; sigma = 0 is
// Lambertian. Two-sided; sampled with the cosine distribution (the lobe is close to Lambertian).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "material/bsdf.h"

namespace torte {

struct OrenNayarBsdf {
  Rgb albedo;
  float sigma = 0;  // radians

  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi)) return {};
    const float s2 = sigma * sigma;
    const float a = 1 - s2 / (2 * (s2 + 0.33f)), b = 0.45f * s2 / (s2 + 0.09f);
    const float cos_o = std::fabs(wo.z), cos_i = std::fabs(wi.z);
    const float sin_o = std::sqrt(std::max(0.0f, 1 - cos_o * cos_o));
    const float sin_i = std::sqrt(std::max(0.0f, 1 - cos_i * cos_i));
    // cos(phi_i - phi_o) = cos phi_i cos phi_o + sin phi_i sin phi_o = (wi.xy . wo.xy) / (sin_i sin_o).
    float cos_dphi = 0;
    if (sin_i > 1e-4f && sin_o > 1e-4f) cos_dphi = std::max(0.0f, (wi.x * wo.x + wi.y * wo.y) / (sin_i * sin_o));
    // sin(alpha) tan(beta): the larger angle gives sin, the smaller tan (written symmetrically for reciprocity).
    const float sin_alpha = cos_i > cos_o ? sin_o : sin_i;
    const float tan_beta = cos_i > cos_o ? sin_i / cos_i : sin_o / cos_o;
    return albedo * (kInvPi * (a + b * cos_dphi * sin_alpha * tan_beta));
  }
  float pdf(Vec3f wo, Vec3f wi) const {
    if (!same_hemisphere(wo, wi)) return 0;
    return cosine_hemisphere_pdf(std::fabs(wi.z));
  }
  bool has_non_specular() const { return true; }
  bool sample(Vec3f wo, float /*uc*/, Vec2f u, BsdfSample* s) const {
    Vec3f wi = sample_cosine_hemisphere(u);
    if (wo.z < 0) wi.z = -wi.z;
    const float p = cosine_hemisphere_pdf(std::fabs(wi.z));
    if (p <= 0 || wo.z == 0) return false;
    s->wi = wi;
    s->f = eval(wo, wi);
    s->pdf = p;
    s->flags = kBsdfReflection;
    s->eta = 1;
    return true;
  }
};

}  // namespace torte
