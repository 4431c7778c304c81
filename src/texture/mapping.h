// Texture-space mappings of a shading point (the inputs of 2D and 3D patterns). All take the point already in
// the mapping's own space (the inverse of the mapping's transform applied). Conventions (y is up, as in scenes):
//   spherical:   u = atan2(z, x) / 2pi wrapped to [0, 1) (u = 0 on +x, 0.25 on +z), v = 1 - theta / pi with
//                theta the angle from +y (v = 1 at the north pole +y, 0 at the south pole, 0.5 on the equator).
//   cylindrical: u as spherical, v = y (the height along the +y axis, unscaled).
//   planar:      (dot(p, s_axis) + offset.x, dot(p, t_axis) + offset.y).
#pragma once
#include "core/vec.h"

namespace torte {

Vec2f spherical_mapping(Vec3f p);
Vec2f cylindrical_mapping(Vec3f p);
inline Vec2f planar_mapping(Vec3f p, Vec3f s_axis, Vec3f t_axis, Vec2f offset) {
  return {dot(p, s_axis) + offset.x, dot(p, t_axis) + offset.y};
}

}  // namespace torte
