// Integrator `path`: unidirectional path tracing with next-event estimation and BSDF sampling combined by MIS
// (power heuristic), Russian roulette on the throughput.
//
//   parameter           type   default  meaning
//   max_depth           int    64       largest number of scattering events on a path (0: emitters only)
//   rr_depth            int    3        Russian roulette from this many scattering events on
//   sample_all_lights   bool   false    one shadow ray per light at every vertex instead of one light by power
#pragma once
#include <atomic>

#include "render/render.h"

namespace torte {

struct PathSettings {
  int max_depth = 64;
  int rr_depth = 3;
  bool sample_all_lights = false;
  static PathSettings from(const RenderSettings& s) { return {s.max_depth, s.rr_depth, s.sample_all_lights}; }
  TransportRules rules() const { return {max_depth, rr_depth, sample_all_lights, false}; }
};

/// Renders with path tracing (settings already validated, camera made for their size).
RenderOutput render_path(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         ProgressSink* progress, const std::atomic<bool>* cancel);

/// The wavefront over camera paths with the given transport rules and no extra stage (path and direct).
RenderOutput render_camera_paths(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                                 const TransportRules& rules, ProgressSink* progress,
                                 const std::atomic<bool>* cancel);

}  // namespace torte
