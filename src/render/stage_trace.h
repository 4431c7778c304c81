// Stages: trace the ray queue (hits in queue order) and trace shadow rays (adding the unoccluded ones'
// radiance to their paths). Both call the Scene's SoA entry points directly on the queues' arrays.
#pragma once
#include <cstdint>
#include <vector>

#include "render/path_state.h"
#include "render/render_settings.h"

namespace torte {

/// Writes hits.hit[k] for every ray k of `rays` (hits is resized to the queue). `coherent`: rays come in groups
/// of neighbours (a tile's camera rays), traced as packets.
inline void trace_rays(const Scene& scene, const RayQueue& rays, HitQueue& hits, bool coherent) {
  hits.resize(rays.size());
  if (rays.size() != 0) scene.intersect(rays.soa(), rays.size(), hits.hit.data(), coherent);
}

/// Traces the shadow rays and adds the contribution of each unoccluded one to its path's radiance, in queue
/// order. `occluded` is scratch. Counts the rays in stats.shadow_rays.
inline void trace_shadows(const Scene& scene, const ShadowQueue& shadows, PathState& paths,
                          std::vector<uint8_t>& occluded, RenderStats& stats, bool coherent = false) {
  const size_t n = shadows.size();
  if (n == 0) return;
  occluded.resize(n);
  scene.occluded(shadows.soa(), n, occluded.data(), coherent);
  for (size_t k = 0; k < n; ++k)
    if (!occluded[k]) paths.radiance[shadows.path[k]] += shadows.contribution[k];
  stats.shadow_rays += n;
  if (stats.stages.enabled) {
    StageTime& t = stats.stages[Stage::Shadows];
    for (size_t k = 0; k < n; ++k) t.blocked += occluded[k] != 0;
    t.tested += n;
  }
}

}  // namespace torte
