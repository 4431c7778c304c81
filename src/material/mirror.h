// Perfect specular reflection (an ideal mirror), optionally tinted. Two-sided like every opaque BSDF.
#pragma once
#include <cmath>

#include "material/bsdf.h"

namespace torte {

struct MirrorBsdf {
  Rgb tint{1};

  Rgb eval(Vec3f, Vec3f) const { return {}; }   // a delta lobe has no density to evaluate
  float pdf(Vec3f, Vec3f) const { return 0; }
  bool has_non_specular() const { return false; }
  bool sample(Vec3f wo, float /*uc*/, Vec2f /*u*/, BsdfSample* s) const {
    if (wo.z == 0) return false;
    s->wi = Vec3f(-wo.x, -wo.y, wo.z);
    s->f = tint / std::fabs(wo.z);  // the delta's coefficient: weight() = tint
    s->pdf = 1;
    s->flags = kBsdfReflection | kBsdfSpecular;
    s->eta = 1;
    return true;
  }
};

}  // namespace torte
