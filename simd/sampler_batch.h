// The Owen-scrambled Sobol points of core/sampler.h for many (pixel, sample, dimension) requests at once: the
// scrambling is a chain of integer hashes and bit reversals per point, which a vector lane does as well as a
// scalar register, so a shading queue's numbers cost a fraction of what they cost one at a time. Highway code
// (sampler_batch.cc) dispatched at run time to the best target the CPU supports, like simd/traverse.h; the
// results are bit for bit those of Sampler::get_2d (tests/test_sampler_batch.cc, on every target).
#pragma once
#include <cstddef>
#include <cstdint>

namespace torte {

/// The scrambling seeds of one request (sampler_detail::derive_seeds): the index shuffle's and each coordinate's.
struct SobolSeedsSoA {
  const uint32_t *shuffle, *a, *b;
};

/// x[k] (and y[k] when y is not null) = the point of request k given its sample index and seeds: exactly
/// Sampler::get_2d's arithmetic after derive_seeds. `count` need not be a multiple of the vector width.
void sobol_points_soa(size_t count, const uint32_t* sample, const SobolSeedsSoA& seeds, float* x, float* y);

/// Name of the Highway target sobol_points_soa dispatches to on this CPU (e.g. "AVX3").
const char* sampler_batch_target_name();

}  // namespace torte
