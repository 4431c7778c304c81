// Padded Owen-scrambled Sobol sampler after Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)),
// and pbrt-v4's PaddedSobolSampler. Only the first two Sobol dimensions are used: together they form a
// (0,2)-sequence, so every aligned block of 2^m consecutive indices is a (0,m,2)-net (one point in each
// elementary interval of area 2^-m). Higher dimensions are "padded" by giving every dimension pair its own
// random index shuffle and its own scrambles instead of using higher Sobol dimensions, whose 2D projections
// are far less well distributed. The hot path is inline in sampler.h; this file has the reference spelling.
#include "core/sampler.h"

#include "simd/sampler_batch.h"

namespace torte {

using namespace sampler_detail;

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

uint32_t sobol_dim0(uint32_t index) { return reverse_bits(index); }

uint32_t sobol_dim1(uint32_t index) {
  const auto& t = kSobolDim1.t;
  return t[0][index & 0xff] ^ t[1][(index >> 8) & 0xff] ^ t[2][(index >> 16) & 0xff] ^ t[3][index >> 24];
}

uint32_t owen_scramble(uint32_t v, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(v), seed));
}

void Sampler::get_batch(size_t count, const uint32_t* pixel, const uint32_t* sample, const uint32_t* dimension, float* x,
                        float* y, uint32_t* scratch) const {
  if (primary_) {  // Metropolis chains: their own numbers, one by one
    for (size_t k = 0; k < count; ++k) {
      const Vec2f u = primary_->get_2d(sample[k], dimension[k]);
      x[k] = u.x;
      if (y) y[k] = u.y;
    }
    return;
  }
  // The seeds need 64-bit multiplies, which AVX2 lanes lack: scalar, and a small share of the work.
  uint32_t *shuffle = scratch, *a = scratch + count, *b = scratch + 2 * count;
  for (size_t k = 0; k < count; ++k) {
    const Seeds s = derive_seeds(seed_hash_, pixel[k], dimension[k]);
    shuffle[k] = s.shuffle, a[k] = s.a, b[k] = s.b;
  }
  sobol_points_soa(count, sample, {shuffle, a, b}, x, y);
}

Vec2f Sampler::get_2d_reference(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const {
  const Seeds s = derive_seeds(seed_hash_, pixel, dimension);
  const uint32_t index = owen_scramble(sample_index, s.shuffle);
  return {to_unit_float(owen_scramble(sobol_dim0(index), s.a)), to_unit_float(owen_scramble(sobol_dim1(index), s.b))};
}

}  // namespace torte
