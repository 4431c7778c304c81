// What a render is asked for (RenderSettings, as torte.render{} fills it) and what it reports (RenderStats).
// Low-level render files include this, not the driver header render.h. Each integrator reads its own parameter
// block out of RenderSettings (PathSettings, DirectSettings in render/integrator_path.h, IgiSettings in
// render/integrator_igi.h); the shared stages see only TransportRules (render/path_state.h).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "camera/camera.h"
#include "film/filter.h"
#include "render/stage_stats.h"

namespace torte {

enum class IntegratorKind : uint8_t {
  Path,    // path tracing: next-event estimation + BSDF sampling with MIS, Russian roulette
  Direct,  // direct lighting only (MIS between light and BSDF sampling); equals Path at max_depth 1
  Igi,     // instant global illumination (render/integrator_igi.h): Direct plus indirect light from VPLs
  Lt,      // light tracing (render/integrator_lt.h): light paths connected to the camera and splatted
  Bdpt,    // bidirectional path tracing (render/integrator_bdpt.h): every (s, t) strategy, MIS-weighted
  Vcm,     // vertex connection and merging (render/integrator_vcm.h): bdpt's strategies plus photon merging
  Ppm,     // progressive photon mapping: vcm's merging only (render/integrator_vcm.h)
  Mlt,     // primary-sample-space Metropolis over bdpt's samples (render/integrator_mlt.h)
};

// Integrators whose light paths connect to the camera and splat (the film keeps a splat sum per pixel).
inline bool splats_to_film(IntegratorKind k) {
  return k == IntegratorKind::Lt || k == IntegratorKind::Bdpt || k == IntegratorKind::Vcm || k == IntegratorKind::Ppm ||
         k == IntegratorKind::Mlt;
}

/// The name scenes select the integrator by (`integrator = "..."`).
inline const char* integrator_name(IntegratorKind k) {
  constexpr const char* names[] = {"path", "direct", "igi", "lt", "bdpt", "vcm", "ppm", "mlt"};
  return names[int(k)];
}

// Integrators whose light paths connect to the lens (the camera must allow it, Camera::connect_problem).
inline bool connects_to_camera(IntegratorKind k) { return splats_to_film(k); }

// Integrators whose every sample lands in its own pixel, so a pixel may stop sampling on its own (noise_threshold).
inline bool supports_adaptive_sampling(IntegratorKind k) { return !splats_to_film(k); }

// Direct and Igi follow camera paths through specular chains only (the lighting they leave out is reached by
// light sampling at every vertex, so torte.render{} samples all lights by default for them).
inline bool ends_after_first_scatter(IntegratorKind k) {
  return k == IntegratorKind::Direct || k == IntegratorKind::Igi;
}

// Bounds of what render() accepts: the pixel count (a 16384x16384 image) and the samples per pixel.
constexpr uint64_t kMaxRenderPixels = uint64_t(1) << 28;
constexpr int kMaxSpp = 1 << 24;

// How next-event estimation picks the light for a shading point: by a light BVH from that point (light/light_bvh.h:
// nearby, facing lights first) or by power alone (one table for every point).
enum class LightSamplerKind : uint8_t { Bvh, Power };

struct RenderSettings {
  int width = 512, height = 512;
  int spp = 16;
  // Largest number of scattering events on a path: 0 shows emitters only, 1 direct light, ...
  int max_depth = 64;
  IntegratorKind integrator = IntegratorKind::Path;
  uint64_t seed = 0;
  Filter filter = Filter::box();
  int rr_depth = 3;                // Russian roulette from this many scattering events on
  bool sample_all_lights = false;  // one shadow ray per light at every vertex instead of one light by power
  LightSamplerKind light_sampler = LightSamplerKind::Bvh;  // for the one light (camera paths' NEE)
  int tile_size = 16;
  // Instant global illumination only: see IgiSettings (render/integrator_igi.h) for their meaning.
  int vpl_sets = 4;
  int light_paths = 64;
  float g_limit = 20;
  float vpl_roulette = 0.25f;
  // vcm and ppm only: see VcmSettings (render/integrator_vcm.h).
  float merge_radius = 0.01f;
  float merge_alpha = 0.75f;
  // mlt only: see MltSettings (render/integrator_mlt.h).
  float large_step = 0.3f;
  int chains = 0;  // 0: chosen from the image size and spp
  // Adaptive sampling (render/adaptive_sampling.h): 0 off, else a pixel stops when its relative error (and its
  // neighbours') is below this, judged at pass boundaries from adaptive_min_spp samples on. Camera integrators only.
  float noise_threshold = 0;
  int adaptive_min_spp = 16;
  double time_limit = 0;     // seconds; 0: none. The render stops at the first pass boundary after it.
  bool stage_stats = false;  // collect RenderStats::stages (torte --stats): one clock reading per stage call
  // Also return each pixel's variance estimate (RenderOutput::variance: the denoiser's noise level, the "variance"
  // AOV). Camera integrators only: splatted light has no per-pixel samples to take it from.
  bool pixel_variance = false;
  // Checkpoints and resuming (render/render_control.h); null: neither. Not part of what the image depends on.
  const struct RenderControl* control = nullptr;
};

/// What the shared stages need to know about the light transport an integrator wants.
struct TransportRules {
  int max_depth = 64;              // scattering events on a path
  int rr_depth = 3;                // Russian roulette from this many events on
  bool sample_all_lights = false;  // next-event estimation towards every light instead of one by power
  bool specular_chains_only = false;  // end at the next hit after the first non-specular event (direct light)
  bool add_emission = true;  // false for light paths: emitters their rays find add nothing (add_emission)
  LightSamplerKind light_sampler = LightSamplerKind::Bvh;  // set from RenderSettings by Wavefront
};

struct RenderStats {
  uint64_t camera_rays = 0, extension_rays = 0, shadow_rays = 0;
  uint64_t dropped_samples = 0;  // NaN or infinite radiance, never added to the film
  uint64_t samples_done = 0;     // camera samples that reached the film (or were dropped)
  double render_seconds = 0;
  bool interrupted = false;
  bool time_limited = false;  // stopped by RenderSettings::time_limit before every pass was rendered
  int spp_reached = 0;        // samples per pixel of the passes completed (the most any pixel took)
  // A distributed render (rank 0): the (tile, pass) units of this render and how many other ranks rendered.
  uint64_t units = 0, remote_units = 0;
  StageStats stages;  // the per-stage profile, filled when RenderSettings::stage_stats is set
  uint64_t rays() const { return camera_rays + extension_rays + shadow_rays; }
  void add(const RenderStats& o) {
    camera_rays += o.camera_rays;
    extension_rays += o.extension_rays;
    shadow_rays += o.shadow_rays;
    dropped_samples += o.dropped_samples;
    samples_done += o.samples_done;
    stages.add(o.stages);
  }
};

/// One invalid setting: `key` names it as torte.render{} does ("spp"), `problem` ends the sentence
/// ("must be in [1, 16777216], got 0"). The one validation of RenderSettings: torte.render{} reports a problem
/// under its keyword before the scene is built; render() refuses the same settings with the same rule.
struct SettingsProblem {
  const char* key;
  std::string problem;
  /// The whole sentence, for errors outside Lua: "'spp' must be in [1, 16777216], got 0".
  std::string message() const { return "'" + std::string(key) + "' " + problem; }
};

/// The first setting of `s` that render() does not accept (the integrators' own ones included), or nothing.
std::optional<SettingsProblem> find_settings_problem(const RenderSettings& s);

/// Throws torte::Error with the first problem's message, or when `camera` was made for an image size other than
/// the settings' (its rays would not cover the image).
void validate(const RenderSettings& s, const Camera& camera);

}  // namespace torte
