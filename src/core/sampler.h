// Low-discrepancy sampler: Owen-scrambled Sobol (0,2)-sequence points, "padded" per dimension pair (as in
// pbrt-v4's PaddedSobolSampler, after Burley 2020). Stateless: a value depends only on (seed, pixel, sample
// index, dimension), so images never depend on thread count or scheduling, and a wavefront can draw any
// path's numbers in any order. Each 2D dimension pair gets its own hash-derived Owen scramble and its own
// index shuffle, which decorrelates pairs while keeping each pair stratified for power-of-two sample counts.
//
// get_2d / get_1d are always inlined: the render loop draws several per path and bounce, and as out-of-line calls
// they were 10 % of a Cornell box render (clang called get_2d out of line when it was merely inline). sampler.cc
// keeps the plain composition (get_2d_reference) that tests hold the inline arithmetic to, bit for bit.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "core/primary_samples.h"
#include "core/rng.h"
#include "core/vec.h"

namespace torte {

namespace sampler_detail {

constexpr uint32_t reverse_bits(uint32_t x) {
  // Byte swap (one instruction), then reverse the bits inside each byte in three swap steps.
  x = __builtin_bswap32(x);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
}

// Reverses the bits of two 32-bit values at the price of one: reverse64(hi:lo) = reverse32(lo):reverse32(hi).
constexpr uint64_t reverse_bits64(uint64_t x) {
  x = __builtin_bswap64(x);
  x = ((x >> 4) & 0x0f0f0f0f0f0f0f0fULL) | ((x & 0x0f0f0f0f0f0f0f0fULL) << 4);
  x = ((x >> 2) & 0x3333333333333333ULL) | ((x & 0x3333333333333333ULL) << 2);
  return ((x >> 1) & 0x5555555555555555ULL) | ((x & 0x5555555555555555ULL) << 1);
}

// Laine & Karras 2011 hash with Burley's constants. Addition, and xor with a multiple by an even constant, only
// carry information from low bits to high bits, so output bit i depends on input bits 0..i only. Applied to
// bit-reversed values that becomes "each digit is flipped depending on the more significant digits only",
// which is exactly Owen's nested uniform scrambling.
constexpr uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Maps a 32-bit fixed-point value in [0, 2^32) to a float in [0, 1). The conversion rounds to nearest, so the
// largest values would round up to 1; clamp to the largest float below 1.
inline float to_unit_float(uint32_t x) { return std::min(float(x) * 0x1p-32f, 0x1.fffffep-1f); }

// The three 32-bit seeds one (pixel, dimension) pair needs: one for the index shuffle, one per coordinate.
struct Seeds {
  uint32_t shuffle, a, b;
};

constexpr Seeds derive_seeds(uint64_t seed_hash, uint32_t pixel, uint32_t dimension) {
  // One 64-bit finalizer over (pixel, dimension) xor the pre-hashed seed gives two independent 32-bit seeds; a
  // multiply by an odd constant (a bijection of the 64-bit hash) gives the third. Nearby keys and nearby seeds
  // both end up unrelated because mix_bits avalanches every input bit.
  const uint64_t key = (uint64_t(pixel) << 32) | dimension;
  const uint64_t h = mix_bits(key ^ seed_hash);
  const uint64_t h2 = h * 0x9e3779b97f4a7c15ULL;
  return {uint32_t(h), uint32_t(h >> 32), uint32_t(h2 >> 32)};
}

// Sobol's second dimension is linear over GF(2) in the index bits (direction numbers v_0 = 2^31,
// v_k = v_{k-1} xor (v_{k-1} >> 1)), and so is reverse(sobol_dim1(reverse(r))): these byte tables give it as
// U[0][r & 255] ^ U[1][(r >> 8) & 255] ^ U[2][...] ^ U[3][r >> 24]. get_2d has the bit-reversed shuffled index
// r at hand and needs the bit-reversed Sobol value, so two bit reversals drop out.
struct ReversedSobolDim1Tables {
  uint32_t u[4][256];
};

constexpr ReversedSobolDim1Tables make_reversed_sobol_dim1_tables() {
  uint32_t v[32] = {};
  v[0] = 1u << 31;
  for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  ReversedSobolDim1Tables t{};
  for (int byte = 0; byte < 4; ++byte)
    for (uint32_t b = 0; b < 256; ++b) {
      uint32_t r = 0;
      for (int bit = 0; bit < 8; ++bit)  // bit m of r is bit 31 - m of the index
        if (b & (1u << bit)) r ^= reverse_bits(v[31 - (8 * byte + bit)]);
      t.u[byte][b] = r;
    }
  return t;
}

inline constexpr ReversedSobolDim1Tables kReversedSobolDim1 = make_reversed_sobol_dim1_tables();

}  // namespace sampler_detail

class Sampler {
 public:
  explicit Sampler(uint64_t seed = 0) : seed_(seed), seed_hash_(mix_bits(seed + 0x9e3779b97f4a7c15ULL)) {}
  uint64_t seed() const { return seed_; }
  /// The point of 2D dimension pair `dimension` for (pixel, sample_index): Owen-scrambled Sobol dimensions 0 and
  /// 1 at an Owen-shuffled index. dimension counts pairs and singles alike: callers give each use its own number.
  [[gnu::always_inline]] Vec2f get_2d(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const {
    if (primary_) [[unlikely]]
      return primary_->get_2d(sample_index, dimension);
    using namespace sampler_detail;
    const Seeds s = derive_seeds(seed_hash_, pixel, dimension);
    // Owen-scrambling the index permutes it within every aligned power-of-two block (index bit k is flipped
    // depending only on the bits above it), so the first 2^m shuffled indices are still one aligned block of the
    // (0,2)-sequence and stay a (0,m,2)-net, while different dimension pairs visit their points in unrelated
    // orders. r is the shuffled index bit-reversed: owen_scramble(i) = reverse(LK(reverse(i))).
    const uint32_t r = laine_karras_permutation(reverse_bits(sample_index), s.shuffle);
    // x: owen_scramble(sobol_dim0(index)) = reverse(LK(index)); y: owen_scramble(sobol_dim1(index)) =
    // reverse(LK(reverse(sobol_dim1(index)))), the inner part read from r by the tables.
    const auto& u = kReversedSobolDim1.u;
    const uint32_t x = laine_karras_permutation(reverse_bits(r), s.a);
    const uint32_t y = laine_karras_permutation(u[0][r & 0xff] ^ u[1][(r >> 8) & 0xff] ^ u[2][(r >> 16) & 0xff] ^
                                                    u[3][r >> 24],
                                                s.b);
    const uint64_t both = reverse_bits64((uint64_t(y) << 32) | x);  // reverse(x) : reverse(y)
    return {to_unit_float(uint32_t(both >> 32)), to_unit_float(uint32_t(both))};
  }
  /// get_2d(pixel, sample_index, dimension).x, without computing y.
  [[gnu::always_inline]] float get_1d(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const {
    if (primary_) [[unlikely]]
      return primary_->get_2d(sample_index, dimension).x;
    using namespace sampler_detail;
    const Seeds s = derive_seeds(seed_hash_, pixel, dimension);
    const uint32_t r = laine_karras_permutation(reverse_bits(sample_index), s.shuffle);
    return to_unit_float(reverse_bits(laine_karras_permutation(reverse_bits(r), s.a)));
  }
  /// Many points at once: x[k] (and y[k] unless y is null) = get_2d(pixel[k], sample[k], dimension[k]), bit for bit,
  /// the scrambling done in vector lanes (simd/sampler_batch.h). `scratch` holds at least 3 * count words.
  void get_batch(size_t count, const uint32_t* pixel, const uint32_t* sample, const uint32_t* dimension, float* x,
                 float* y, uint32_t* scratch) const;
  /// From now on (until called with null) get_2d(pixel, s, d) reads coordinates d of Markov chain s of
  /// `primary` instead (Metropolis light transport, render/integrator_mlt.h); the pixel is then ignored.
  void use_primary_samples(const PrimarySamples* primary) { primary_ = primary; }
  /// get_2d spelled as the plain composition of sobol_dim0/1 and owen_scramble below (for tests).
  Vec2f get_2d_reference(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const;

 private:
  uint64_t seed_;
  uint64_t seed_hash_;  // mix_bits of the seed, computed once: every sample needs it
  const PrimarySamples* primary_ = nullptr;
};

// Building blocks, exposed for tests.
uint32_t sobol_dim0(uint32_t index);  // van der Corput (bit reversal)
uint32_t sobol_dim1(uint32_t index);  // Sobol's second dimension
uint32_t owen_scramble(uint32_t v, uint32_t seed);  // nested uniform scramble (Burley 2020, Laine-Karras hash)

}  // namespace torte
