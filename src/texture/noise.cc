#include "texture/noise.h"

#include <cmath>

namespace torte {

namespace {

// 32-bit integer hash (lowbias32, Chris Wellons), seeded per lattice point.
inline uint32_t mix32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}
inline uint32_t hash(int32_t x, int32_t y, uint32_t seed) {
  return mix32(uint32_t(x) ^ mix32(uint32_t(y) ^ mix32(seed + 0x9e3779b9U)));
}
inline uint32_t hash(int32_t x, int32_t y, int32_t z, uint32_t seed) {
  return mix32(uint32_t(x) ^ mix32(uint32_t(y) ^ mix32(uint32_t(z) ^ mix32(seed + 0x9e3779b9U))));
}
// A lattice value in [-1, 1].
inline float to_signed(uint32_t h) { return float(h >> 8) * (2.0f / 16777215.0f) - 1.0f; }

inline float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }
inline float lerp(float t, float a, float b) { return a + t * (b - a); }

inline float grad2(uint32_t h, float x, float y) {
  // 8 unit directions: the axes and the diagonals.
  constexpr float d = 0.70710678f;
  switch (h & 7) {
    case 0: return x;
    case 1: return -x;
    case 2: return y;
    case 3: return -y;
    case 4: return d * (x + y);
    case 5: return d * (x - y);
    case 6: return d * (-x + y);
    default: return d * (-x - y);
  }
}
inline float grad3(uint32_t h, float x, float y, float z) {
  // Perlin's 12 cube-edge directions (16 cases, 4 repeated).
  switch (h & 15) {
    case 0: case 12: return x + y;
    case 1: case 13: return -x + y;
    case 2: return x - y;
    case 3: return -x - y;
    case 4: return x + z;
    case 5: return -x + z;
    case 6: return x - z;
    case 7: return -x - z;
    case 8: return y + z;
    case 9: case 14: return -y + z;
    case 10: return y - z;
    default: return -y - z;  // 11, 15
  }
}

inline float clamp1(float v) { return v < -1 ? -1 : (v > 1 ? 1 : v); }

// A floored coordinate as a lattice index, wrapped to 32 bits like the hash: converting a float beyond 2^31 (or
// NaN) to int32_t directly is undefined behaviour, and scene coordinates reach 1e18.
inline int32_t lattice(float f) {
  if (std::fabs(f) < 2147483648.0f) return int32_t(f);
  if (!std::isfinite(f)) return 0;
  return int32_t(uint32_t(int64_t(std::fmod(double(f), 4294967296.0))));
}

}  // namespace

float value_noise(Vec2f p, uint32_t seed) {
  const float fx = std::floor(p.x), fy = std::floor(p.y);
  const int32_t x = lattice(fx), y = lattice(fy);
  const float u = fade(p.x - fx), v = fade(p.y - fy);
  return lerp(v, lerp(u, to_signed(hash(x, y, seed)), to_signed(hash(x + 1, y, seed))),
              lerp(u, to_signed(hash(x, y + 1, seed)), to_signed(hash(x + 1, y + 1, seed))));
}

float value_noise(Vec3f p, uint32_t seed) {
  const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int32_t x = lattice(fx), y = lattice(fy), z = lattice(fz);
  const float u = fade(p.x - fx), v = fade(p.y - fy), w = fade(p.z - fz);
  auto val = [&](int dx, int dy, int dz) { return to_signed(hash(x + dx, y + dy, z + dz, seed)); };
  return lerp(w,
              lerp(v, lerp(u, val(0, 0, 0), val(1, 0, 0)), lerp(u, val(0, 1, 0), val(1, 1, 0))),
              lerp(v, lerp(u, val(0, 0, 1), val(1, 0, 1)), lerp(u, val(0, 1, 1), val(1, 1, 1))));
}

float perlin_noise(Vec2f p, uint32_t seed) {
  const float fx = std::floor(p.x), fy = std::floor(p.y);
  const int32_t x = lattice(fx), y = lattice(fy);
  const float rx = p.x - fx, ry = p.y - fy;
  const float u = fade(rx), v = fade(ry);
  const float n = lerp(v, lerp(u, grad2(hash(x, y, seed), rx, ry), grad2(hash(x + 1, y, seed), rx - 1, ry)),
                       lerp(u, grad2(hash(x, y + 1, seed), rx, ry - 1),
                            grad2(hash(x + 1, y + 1, seed), rx - 1, ry - 1)));
  // With unit gradients |n| <= sqrt(2)/2 (reached at cell centres with aligned diagonal gradients).
  return clamp1(n * 1.41421356f);
}

float perlin_noise(Vec3f p, uint32_t seed) {
  const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int32_t x = lattice(fx), y = lattice(fy), z = lattice(fz);
  const float rx = p.x - fx, ry = p.y - fy, rz = p.z - fz;
  const float u = fade(rx), v = fade(ry), w = fade(rz);
  auto g = [&](int dx, int dy, int dz) {
    return grad3(hash(x + dx, y + dy, z + dz, seed), rx - float(dx), ry - float(dy), rz - float(dz));
  };
  const float n = lerp(w, lerp(v, lerp(u, g(0, 0, 0), g(1, 0, 0)), lerp(u, g(0, 1, 0), g(1, 1, 0))),
                       lerp(v, lerp(u, g(0, 0, 1), g(1, 0, 1)), lerp(u, g(0, 1, 1), g(1, 1, 1))));
  // Edge gradients (length sqrt 2): |n| stays below ~1.04 in practice; clamp keeps the documented range exact.
  return clamp1(n);
}

float noise_texture(const NoiseParams& params, Vec3f p) {
  auto basis = [&](Vec3f q, uint32_t seed) {
    if (params.dims == 2) {
      const Vec2f q2(q.x, q.y);
      return params.basis == NoiseBasis::Value ? value_noise(q2, seed) : perlin_noise(q2, seed);
    }
    return params.basis == NoiseBasis::Value ? value_noise(q, seed) : perlin_noise(q, seed);
  };
  if (params.fractal == NoiseFractal::None) return 0.5f + 0.5f * basis(p, params.seed);
  float sum = 0, norm = 0, amplitude = 1;
  Vec3f q = p;
  for (int k = 0; k < params.octaves; ++k) {
    const float n = basis(q, params.seed + uint32_t(k) * 0x632be5abU);
    sum += amplitude * (params.fractal == NoiseFractal::Turbulence ? std::fabs(n) : n);
    norm += amplitude;
    amplitude *= params.gain;
    q = q * params.lacunarity;
  }
  const float v = sum / norm;
  return params.fractal == NoiseFractal::Turbulence ? v : 0.5f + 0.5f * v;
}

}  // namespace torte
