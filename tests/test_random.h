// Random inputs shared by the unit tests (deterministic: every test seeds its own Pcg32).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "core/vec.h"

namespace torte::test {

// Uniform in [0, 1)^3.
inline Vec3f random_vec(Pcg32& rng) { return {rng.next_float(), rng.next_float(), rng.next_float()}; }

// Uniform on the unit sphere.
inline Vec3f random_direction(Pcg32& rng) {
  const float z = 1 - 2 * rng.next_float(), phi = 2 * kPi * rng.next_float();
  const float r = std::sqrt(std::max(0.0f, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform in [0, 1)^2 (x drawn first).
inline Vec2f next_2d(Pcg32& rng) {
  const float x = rng.next_float();
  return {x, rng.next_float()};
}

}  // namespace torte::test
