// Environment light from an equirectangular image, importance-sampled over the whole sphere.
//
// Parameterization (light space, +y up): a direction (x, y, z) has theta = acos(y) in [0, pi] measured from +y
// and phi = atan2(z, x) in [0, 2 pi); the image coordinate is (u, v) = (phi / 2 pi, theta / pi), so the top row
// is straight up, the bottom row straight down, u = 0 looks along +x and u = 0.25 along +z. A light-to-world
// rotation places the map in the scene.
//
// Lookup is nearest-texel, so radiance is piecewise constant over texels exactly like the sampling density: a
// Distribution2D over the texels weighted by average radiance x sin(theta at the row centre). The solid-angle
// density of a direction is p(u, v) / (2 pi^2 sin theta), which integrates to 1 over the full sphere (lower
// hemisphere included).
#pragma once
#include <memory>
#include <vector>

#include "core/rgb.h"
#include "core/sampling.h"
#include "core/transform.h"

namespace torte {

struct Image;

Vec3f equirect_direction(Vec2f uv);  // light space, unit
Vec2f equirect_uv(Vec3f d);          // d: unit, light space; result in [0,1)^2

// A tabulated spherical distribution on the equirectangular grid, shared by the environment map and the sky.
struct SphericalDistribution {
  Distribution2D dist;
  Transform to_world;  // rotation (light to world)
  // weights: nu x nv, row-major, already multiplied by sin(theta).
  SphericalDistribution(std::span<const float> weights, int nu, int nv, const Transform& to_world);
  SphericalDistribution() = default;
  // Samples a world direction; false if the density there is zero.
  bool sample(Vec2f u, Vec3f* wi, float* pdf) const;
  float pdf(Vec3f world_dir) const;
  Vec3f to_light(Vec3f world_dir) const { return normalize(to_world.apply_inverse_vector(world_dir)); }
};

struct EnvironmentMap {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;  // already multiplied by the scale
  SphericalDistribution sampling;
  float integral = 0;  // integral of average radiance over the sphere (W/m^2 for unit radiance), for power

  Rgb lookup(Vec3f world_dir) const;
};

// Throws torte::Error for an empty image, negative or non-finite pixels, a transform that is not a rotation
// (times a uniform scale, which does not matter for directions), or tables over the memory budget.
std::shared_ptr<const EnvironmentMap> make_environment_map(const Image& image, const Transform& to_world, Rgb scale);

// True when the linear part of t is a rotation times a uniform scale (within a small tolerance); *scale receives
// that scale factor.
bool is_similarity(const Transform& t, float* scale = nullptr);

}  // namespace torte
