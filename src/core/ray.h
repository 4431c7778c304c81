// A ray with its valid parameter interval [0, t_max]. Origins are offset by the caller (see offset_origin).
#pragma once
#include "core/vec.h"

namespace torte {

struct Ray {
  Vec3f o, d;
  float t_max = kInfinity;
  Vec3f at(float t) const { return o + d * t; }
};

// Moves a surface point off the surface along the geometric normal, on the side of direction w, by an amount
// scaled to the point's magnitude, so rays leaving the surface do not re-hit it through float error.
inline Vec3f offset_origin(Vec3f p, Vec3f ng, Vec3f w) {
  const float scale = 1e-4f * (1.0f + max_component(abs(p)));
  const Vec3f off = ng * scale;
  return dot(w, ng) < 0 ? p - off : p + off;
}

}  // namespace torte
