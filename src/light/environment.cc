#include "light/environment.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/memory_budget.h"
#include "film/image.h"

namespace torte {

Vec3f equirect_direction(Vec2f uv) {
  const float theta = kPi * uv.y, phi = 2 * kPi * uv.x;
  const float s = std::sin(theta);
  return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

Vec2f equirect_uv(Vec3f d) {
  const float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
  float phi = std::atan2(d.z, d.x);
  if (phi < 0) phi += 2 * kPi;
  return {std::min(phi / (2 * kPi), kOneMinusEpsilon), std::min(theta / kPi, kOneMinusEpsilon)};
}

bool is_similarity(const Transform& t, float* scale) {
  const Vec3f a = t.apply_vector({1, 0, 0}), b = t.apply_vector({0, 1, 0}), c = t.apply_vector({0, 0, 1});
  const float la = length(a), lb = length(b), lc = length(c);
  if (!(la > 0) || !(lb > 0) || !(lc > 0)) return false;
  const float tol = 1e-4f;
  const bool ok = std::fabs(la - lb) <= tol * la && std::fabs(la - lc) <= tol * la &&
                  std::fabs(dot(a, b)) <= tol * la * lb && std::fabs(dot(a, c)) <= tol * la * lc &&
                  std::fabs(dot(b, c)) <= tol * lb * lc;
  if (ok && scale) *scale = la;
  return ok;
}

SphericalDistribution::SphericalDistribution(std::span<const float> weights, int nu, int nv,
                                             const Transform& to_world_)
    : dist(weights, nu, nv), to_world(to_world_) {}

bool SphericalDistribution::sample(Vec2f u, Vec3f* wi, float* pdf) const {
  float pdf_uv;
  const Vec2f uv = dist.sample(u, &pdf_uv);
  if (!(pdf_uv > 0)) return false;
  *wi = normalize(to_world.apply_vector(equirect_direction(uv)));
  // The density is looked up again from the direction (not from uv) so that it equals pdf() bit for bit.
  *pdf = this->pdf(*wi);
  return *pdf > 0;
}

float SphericalDistribution::pdf(Vec3f world_dir) const {
  const Vec3f d = to_light(world_dir);
  const float sin_theta = std::sqrt(std::max(0.0f, d.x * d.x + d.z * d.z));
  if (!(sin_theta > 0)) return 0;
  return dist.pdf(equirect_uv(d)) / (2 * kPi * kPi * sin_theta);
}

Rgb EnvironmentMap::lookup(Vec3f world_dir) const {
  const Vec2f uv = equirect_uv(sampling.to_light(world_dir));
  const int x = std::clamp(int(uv.x * float(width)), 0, width - 1);
  const int y = std::clamp(int(uv.y * float(height)), 0, height - 1);
  return pixels[size_t(y) * size_t(width) + size_t(x)];
}

std::shared_ptr<const EnvironmentMap> make_environment_map(const Image& image, const Transform& to_world, Rgb scale) {
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * size_t(image.height))
    throw Error("environment map: empty image");
  if (!is_similarity(to_world)) throw Error("environment map: the transform must be a rotation");
  if (!scale.is_finite() || scale.r < 0 || scale.g < 0 || scale.b < 0)
    throw Error("environment map: scale must be finite and non-negative");
  // The radiance copy, the weights, and the sampling tables (a function and a CDF value per texel, per row).
  const uint64_t texels = uint64_t(image.width) * uint64_t(image.height);
  reserve_memory(checked_bytes(texels, sizeof(Rgb) + 3 * sizeof(float), "environment map"),
                 "environment map of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " pixels");
  auto env = std::make_shared<EnvironmentMap>();
  env->width = image.width;
  env->height = image.height;
  env->pixels.resize(image.pixels.size());
  std::vector<float> weights(image.pixels.size());
  double integral = 0;
  const double texel_solid = (2 * M_PI / image.width) * (M_PI / image.height);  // times sin(theta)
  for (int y = 0; y < image.height; ++y) {
    const float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(image.height));
    for (int x = 0; x < image.width; ++x) {
      const size_t i = size_t(y) * size_t(image.width) + size_t(x);
      const Rgb p = image.pixels[i];
      if (!p.is_finite() || p.r < 0 || p.g < 0 || p.b < 0)
        throw Error("environment map: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                    ") is negative or not finite");
      env->pixels[i] = p * scale;
      weights[i] = env->pixels[i].average() * sin_theta;
      integral += double(weights[i]) * texel_solid;
    }
  }
  env->integral = float(integral);
  env->sampling = SphericalDistribution(weights, image.width, image.height, to_world);
  return env;
}

}  // namespace torte
