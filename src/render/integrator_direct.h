// Integrator `direct`: direct lighting only, MIS between light and BSDF sampling. Camera paths follow specular
// chains (mirrors and glass show the lit scene) and end at the next hit after the first non-specular event,
// which still adds the emission found there; equals `path` at max_depth 1.
//
//   parameter           type   default  meaning
//   max_depth           int    64       largest number of scattering events (specular ones included)
//   rr_depth            int    3        Russian roulette from this many events on (long specular chains)
//   sample_all_lights   bool   false    one shadow ray per light at every vertex instead of one light by power
#pragma once
#include <atomic>

#include "render/render.h"

namespace torte {

struct DirectSettings {
  int max_depth = 64;
  int rr_depth = 3;
  bool sample_all_lights = false;
  static DirectSettings from(const RenderSettings& s) { return {s.max_depth, s.rr_depth, s.sample_all_lights}; }
  TransportRules rules() const { return {max_depth, rr_depth, sample_all_lights, true}; }
};

/// Renders direct lighting (settings already validated, camera made for their size).
RenderOutput render_direct(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                           ProgressSink* progress, const std::atomic<bool>* cancel);

}  // namespace torte
