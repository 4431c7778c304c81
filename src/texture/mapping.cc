#include "texture/mapping.h"

#include <cmath>

namespace torte {

namespace {
float azimuth(Vec3f p) {
  if (p.x == 0 && p.z == 0) return 0;
  float u = std::atan2(p.z, p.x) * (0.5f * kInvPi);
  if (u < 0) u += 1;
  return u >= 1 ? 0 : u;  // -0 and rounding
}
}  // namespace

Vec2f spherical_mapping(Vec3f p) {
  const float r = length(p);
  if (r == 0) return {0, 0.5f};
  const float cos_theta = std::clamp(p.y / r, -1.0f, 1.0f);
  return {azimuth(p), 1 - std::acos(cos_theta) * kInvPi};
}

Vec2f cylindrical_mapping(Vec3f p) { return {azimuth(p), p.y}; }

}  // namespace torte
