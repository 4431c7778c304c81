// Lattice noise: value noise and Perlin gradient noise in 2D and 3D, and their fractal sums (fBm, turbulence).
// Deterministic: integer lattice hashing only (no tables, no global state), identical on every platform and
// thread; `seed` selects an independent noise field. All functions are continuous (C2 interpolation: quintic fade).
#pragma once
#include <cstdint>

#include "core/vec.h"

namespace torte {

// Value noise: random lattice values in [-1, 1], interpolated. Output in [-1, 1].
float value_noise(Vec2f p, uint32_t seed = 0);
float value_noise(Vec3f p, uint32_t seed = 0);
// Perlin gradient noise (Perlin 2002 fade; 8 gradient directions in 2D, 12 in 3D), scaled so the output lies
// in [-1, 1] (clamped at the theoretical extremes); 0 at every lattice point.
float perlin_noise(Vec2f p, uint32_t seed = 0);
float perlin_noise(Vec3f p, uint32_t seed = 0);

enum class NoiseBasis : uint8_t { Value, Perlin };
enum class NoiseFractal : uint8_t { None, Fbm, Turbulence };

struct NoiseParams {
  NoiseBasis basis = NoiseBasis::Perlin;
  NoiseFractal fractal = NoiseFractal::None;
  int dims = 3;            // 2: reads p.x, p.y; 3: reads p
  int octaves = 6;         // fBm / turbulence: number of octaves, 1..16
  float lacunarity = 2;    // frequency factor between octaves
  float gain = 0.5f;       // amplitude factor between octaves, in (0, 1]
  uint32_t seed = 0;
};

// The noise texture value, in [0, 1]:
//   None:        0.5 + 0.5 n(p)
//   Fbm:         0.5 + 0.5 (sum_k gain^k n(lacunarity^k p)) / (sum_k gain^k)
//   Turbulence:  (sum_k gain^k |n(lacunarity^k p)|) / (sum_k gain^k)
// Each octave uses a different seed, so octaves are not aligned at the origin.
float noise_texture(const NoiseParams& params, Vec3f p);

}  // namespace torte
