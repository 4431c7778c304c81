// Padded Owen-scrambled Sobol sampler after Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)),
// and pbrt-v4's PaddedSobolSampler. Only the first two Sobol dimensions are used: together they form a
// (0,2)-sequence, so every aligned block of 2^m consecutive indices is a (0,m,2)-net (one point in each
// elementary interval of area 2^-m). Higher dimensions are "padded" by giving every dimension pair its own
// random index shuffle and its own scrambles instead of using higher Sobol dimensions, whose 2D projections
// are far less well distributed.
#include "core/sampler.h"

#include <algorithm>

#include "core/rng.h"

namespace torte {

namespace {

uint32_t reverse_bits(uint32_t x) {
  // Byte swap (one instruction), then reverse the bits inside each byte in three swap steps.
  x = __builtin_bswap32(x);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
}

// Laine & Karras 2011 hash with Burley's constants. Addition, and xor with a multiple by an even constant, only
// carry information from low bits to high bits, so output bit i depends on input bits 0..i only. Applied to
// bit-reversed values that becomes "each digit is flipped depending on the more significant digits only",
// which is exactly Owen's nested uniform scrambling.
uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Maps a 32-bit fixed-point value in [0, 2^32) to a float in [0, 1). The conversion rounds to nearest, so the
// largest values would round up to 1; clamp to the largest float below 1.
float to_unit_float(uint32_t x) { return std::min(float(x) * 0x1p-32f, 0x1.fffffep-1f); }

// The three 32-bit seeds one (pixel, dimension) pair needs: one for the index shuffle, one per coordinate.
struct Seeds {
  uint32_t shuffle, a, b;
};

Seeds derive_seeds(uint64_t seed_hash, uint32_t pixel, uint32_t dimension) {
  // One 64-bit finalizer over (pixel, dimension) xor the pre-hashed seed gives two independent 32-bit seeds; a
  // multiply by an odd constant (a bijection of the 64-bit hash) gives the third. Nearby keys and nearby seeds
  // both end up unrelated because mix_bits avalanches every input bit.
  const uint64_t key = (uint64_t(pixel) << 32) | dimension;
  const uint64_t h = mix_bits(key ^ seed_hash);
  const uint64_t h2 = h * 0x9e3779b97f4a7c15ULL;
  return {uint32_t(h), uint32_t(h >> 32), uint32_t(h2 >> 32)};
}

}  // namespace

Sampler::Sampler(uint64_t seed) : seed_(seed), seed_hash_(mix_bits(seed + 0x9e3779b97f4a7c15ULL)) {}

uint32_t sobol_dim0(uint32_t index) { return reverse_bits(index); }

namespace {

// Sobol's second dimension is linear over GF(2) in the index bits, so it splits into four byte-wise tables:
// result = T0[byte 0] ^ T1[byte 1] ^ T2[byte 2] ^ T3[byte 3]. The scrambled indices use all 32 bits, and a
// bit-by-bit loop there costs 32 unpredictable branches per sample.
struct SobolDim1Tables {
  uint32_t t[4][256];
  SobolDim1Tables() {
    // Direction numbers: v_0 = 1/2, v_k = v_{k-1} xor (v_{k-1} >> 1) (the upper-triangular Pascal matrix mod 2).
    uint32_t v[32];
    v[0] = 1u << 31;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int byte = 0; byte < 4; ++byte)
      for (uint32_t b = 0; b < 256; ++b) {
        uint32_t r = 0;
        for (int bit = 0; bit < 8; ++bit)
          if (b & (1u << bit)) r ^= v[8 * byte + bit];
        t[byte][b] = r;
      }
  }
};

const SobolDim1Tables kSobolDim1;

}  // namespace

uint32_t sobol_dim1(uint32_t index) {
  const auto& t = kSobolDim1.t;
  return t[0][index & 0xff] ^ t[1][(index >> 8) & 0xff] ^ t[2][(index >> 16) & 0xff] ^ t[3][index >> 24];
}

uint32_t owen_scramble(uint32_t v, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(v), seed));
}

Vec2f Sampler::get_2d(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const {
  const Seeds s = derive_seeds(seed_hash_, pixel, dimension);
  // Owen-scrambling the index permutes it within every aligned power-of-two block (index bit k is flipped
  // depending only on the bits above it), so the first 2^m shuffled indices are still one aligned block of the
  // (0,2)-sequence and stay a (0,m,2)-net, while different dimension pairs visit their points in unrelated orders.
  const uint32_t index = owen_scramble(sample_index, s.shuffle);
  // owen_scramble(sobol_dim0(i)) = reverse(LK(reverse(reverse(i)))) = reverse(LK(i)): skip two reversals.
  return {to_unit_float(reverse_bits(laine_karras_permutation(index, s.a))),
          to_unit_float(owen_scramble(sobol_dim1(index), s.b))};
}

float Sampler::get_1d(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const {
  const Seeds s = derive_seeds(seed_hash_, pixel, dimension);
  const uint32_t index = owen_scramble(sample_index, s.shuffle);
  return to_unit_float(reverse_bits(laine_karras_permutation(index, s.a)));
}

}  // namespace torte
