// Instant global illumination (Keller 1997; the seed's "igi" renderer), IntegratorKind::Igi.
//
//   parameter           type   default  meaning
//   max_depth           int    64       scattering events; VPLs are stored up to light-path bounce max_depth - 1
//   rr_depth            int    3        Russian roulette on camera paths (specular chains), as in direct
//   sample_all_lights   bool   false    direct light: one shadow ray per light instead of one light by power
//   vpl_sets            int    4        independent VPL sets per sample index; a camera sample gathers from one
//   light_paths         int    64       light paths per set (each leaves a VPL at every non-specular hit)
//   g_limit             float  20       clamp of the geometry term: G <= g_limit / R^2, R the scene's bounding
//                                       radius (scale-invariant); infinity: no clamp (unbiased, spiky)
//   vpl_roulette        float  0.25     below this fraction of its start throughput a light path continues with
//                                       probability (throughput / start) / vpl_roulette (unbiased); 0: off
//
// Per progressive pass (generate_vpls, render/vpl.h): for every sample index s the pass renders, a family of
// `vpl_sets` independent sets of `light_paths` light paths each, drawn afresh (deterministic from the seed), so
// the estimate converges to the clamped solution as spp grows (before, one family served every sample). A
// path leaves a light chosen by power (light/light_emission.h) and, at every surface hit whose BSDF has a
// non-specular part, stores a virtual point light (VPL): the hit point, its normals, its resolved material with
// the BSDF built in TransportMode::Importance, the direction wo the light arrived from, and the flux the path
// carries divided by light_paths. The path then continues by BSDF sampling; specular-only surfaces pass the
// light on without storing a VPL (caustics reach the next diffuse hit). Russian roulette ends weak paths
// (vpl_roulette). Light paths never store a VPL on the light itself, so the VPLs carry light
// that has bounced at least once: their estimate is INDIRECT light only, and direct light stays with the
// camera side's next-event estimation (exactly as `direct`: MIS between light and BSDF sampling, one or all
// lights). Nothing is counted twice.
//
// Rendering: camera paths run as `direct` (following specular chains; TransportRules::specular_chains_only).
// Every hit shaded with a non-specular BSDF also gathers from the VPLs of one set of its sample's family, chosen
// by interleaved sampling ((hash(pixel) + sample) mod vpl_sets): for VPL y seen from x in direction wi,
//   beta * f_x(wo, wi) * min(G, G_max) * f_y(wo_y, -wi) * power_y,   G = |cos_x| |cos_y| / |x - y|^2,
// queued as a shadow ray (ShadowQueue) and traced in batches. G_max = g_limit / R^2 (R: the scene's bounding
// radius). The clamp removes the bright spots VPLs make next to the surfaces they lie on, and with them the
// energy of short-range inter-reflections (corners get darker): the bias, which goes to zero as g_limit grows.
// A VPL at light-path bounce d adds paths of d + 1 scattering events: VPLs are stored for d <= max_depth - 1.
// Missing, as in `direct`: light reaching the first non-specular camera hit through specular surfaces only
// (L S+ D E caustics: no VPL lies on a light). Caustics that bounce once more (L S+ D D E) are in, through the
// VPLs light paths leave behind specular chains. Unclamped (huge g_limit), VPL estimates are heavy-tailed: with
// few light paths the image mean is usually a little low (scenes/lights.lua, light=spot: -1.4 % with 8 x 256
// light paths, -0.3 % with 32 x 1024).
#pragma once
#include <atomic>

#include "render/render.h"

namespace torte {

struct IgiSettings {
  int max_depth = 64;
  int rr_depth = 3;
  bool sample_all_lights = false;
  int vpl_sets = 4;
  int light_paths = 64;
  float g_limit = 20;
  float vpl_roulette = 0.25f;
  static IgiSettings from(const RenderSettings& s) {
    return {s.max_depth, s.rr_depth, s.sample_all_lights, s.vpl_sets, s.light_paths, s.g_limit, s.vpl_roulette};
  }
};

/// Renders with instant global illumination (settings already validated, camera made for their size).
RenderOutput render_igi(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        ProgressSink* progress, const std::atomic<bool>* cancel);

}  // namespace torte
