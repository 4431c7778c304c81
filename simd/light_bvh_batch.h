// The light BVH's descent (light/light_bvh.h) for many receivers at once, one per vector lane. One descent is a
// chain of dependent node loads and unpredictable left-or-right branches, so one at a time a core mostly waits;
// side by side, the lanes' loads are gathers issued together and the branches are selects. Highway code
// (light_bvh_batch.cc) dispatched at run time like simd/traverse.h; the results are bit for bit those of
// LightBvh::sample as the baseline build compiles it (tests/test_light_bvh.cc, on every target). The render loop's
// AVX2 copy of the scalar code fuses some multiplies and adds, so there its probabilities may differ in the last
// bits; pmf() (the MIS weights) never matched sample() to the bit either (it divides the chosen side's importance
// by the sum where the descent takes 1 - p0), and a relative 1e-7 in a density changes no image.
#pragma once
#include <cstddef>
#include <cstdint>

#include "light/light_bvh.h"

namespace torte {

/// Receivers for light_bvh_descend, structure of arrays: position p, normal n (0: no receiver cosine), the uniform
/// number u and the probability prob the descent starts from (the share left to the bounded lights).
struct LightDescentInput {
  const float *px, *py, *pz, *nx, *ny, *nz, *u, *prob;
};

/// For each k < count, the leaf LightBvh::sample_bounded reaches from the root of `nodes` (an inner node): light[k]
/// its light (-1 where no light can reach the receiver), pmf[k] its probability (0 then), part[k] its part.
void light_bvh_descend(const LightBvh::PackedNode* nodes, size_t count, const LightDescentInput& in, int32_t* light,
                       float* pmf, uint32_t* part);

/// Name of the Highway target light_bvh_descend dispatches to on this CPU (e.g. "AVX2").
const char* light_bvh_batch_target_name();

}  // namespace torte
