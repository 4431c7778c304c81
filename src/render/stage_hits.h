// Stage: from trace results to shading queues. Every hit gets its surface reconstructed (the emission stage,
// stage_emission.h, reads it too); paths that go on get their material resolved (Mix, Bump), and their queue
// slots are counting-sorted by material type into one contiguous queue per type.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/sampler.h"
#include "render/path_state.h"

namespace torte {

/// Queue slots grouped by material type.
struct MaterialQueues {
  std::vector<uint32_t> slots;
  uint32_t begin[kMaterialTypeCount + 1] = {};
  std::vector<uint32_t> unsorted;  // scratch
  std::span<const uint32_t> queue(MaterialType t) const {
    return {slots.data() + begin[int(t)], begin[int(t) + 1] - begin[int(t)]};
  }
};

/// Reconstructs hits.surface[k] for every ray k that hit and queues the paths that go on; `spread` is the
/// camera's ray-cone spread angle. `dim_base` offsets the sampler dimensions Mix materials draw (BDPT's light
/// subpaths use their own, so they do not share numbers with the camera subpath of the same sample).
void sort_hits(const Scene& scene, const TransportRules& rules, const Sampler& sampler, float spread,
               const RayQueue& rays, HitQueue& hits, PathState& paths, MaterialQueues& out, uint32_t dim_base = 0);

}  // namespace torte
