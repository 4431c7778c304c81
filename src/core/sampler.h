// Low-discrepancy sampler: Owen-scrambled Sobol (0,2)-sequence points, "padded" per dimension pair (as in
// pbrt-v4's PaddedSobolSampler, after Burley 2020). Stateless: a value depends only on (seed, pixel, sample
// index, dimension), so images never depend on thread count or scheduling, and a wavefront can draw any
// path's numbers in any order. Each 2D dimension pair gets its own hash-derived Owen scramble and its own
// index shuffle, which decorrelates pairs while keeping each pair stratified for power-of-two sample counts.
#pragma once
#include <cstdint>

#include "core/vec.h"

namespace torte {

class Sampler {
 public:
  explicit Sampler(uint64_t seed = 0);
  uint64_t seed() const { return seed_; }
  // dimension counts pairs and singles alike: callers give each use its own dimension number.
  Vec2f get_2d(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const;
  float get_1d(uint32_t pixel, uint32_t sample_index, uint32_t dimension) const;

 private:
  uint64_t seed_;
  uint64_t seed_hash_;  // mix_bits of the seed, computed once: every sample needs it
};

// Building blocks, exposed for tests.
uint32_t sobol_dim0(uint32_t index);  // van der Corput (bit reversal)
uint32_t sobol_dim1(uint32_t index);  // Sobol's second dimension
uint32_t owen_scramble(uint32_t v, uint32_t seed);  // nested uniform scramble (Burley 2020, Laine-Karras hash)

}  // namespace torte
