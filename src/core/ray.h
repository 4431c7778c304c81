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

/// The ray from `o` (a point already moved off its surface) to `target`, stopping the fraction `shorten` short of
/// it. Aimed at the target itself (pbrt's SpawnRayTo): a ray along the direction w the offset was chosen for
/// passes beside the target by the offset, and a curved surface there could stop it. A target behind o along w
/// (nearer than the offset) gives an empty ray along w (t_max 0), which nothing occludes.
inline Ray ray_towards(Vec3f o, Vec3f target, Vec3f w, float shorten) {
  const Vec3f d = target - o;
  if (!(dot(d, w) > 0)) return {o, w, 0};
  const float len = length(d);
  return {o, d * (1 / len), len * (1 - shorten)};
}

}  // namespace torte
