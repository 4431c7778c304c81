// The render driver: progressive passes over image tiles (TBB), each tile traced as wavefronts of paths.
// Every pixel belongs to exactly one tile and each camera sample only contributes to its own pixel (filter
// importance sampling), so tiles never share film memory and the image is bitwise identical for any thread
// count or schedule.
#pragma once
#include <atomic>
#include <cstdint>

#include "camera/camera.h"
#include "film/filter.h"
#include "film/image.h"
#include "scene/scene.h"

namespace torte {

enum class IntegratorKind : uint8_t {
  Path,    // path tracing: next-event estimation + BSDF sampling with MIS, Russian roulette
  Direct,  // direct lighting only (MIS between light and BSDF sampling); equals Path at max_depth 1
  Igi,     // instant global illumination (render/igi.h): Direct plus indirect light from virtual point lights
};

// Direct and Igi follow camera paths through specular chains only: they end at the next hit after the first
// non-specular scattering event (which still adds the emission found there).
inline bool ends_after_first_scatter(IntegratorKind k) {
  return k == IntegratorKind::Direct || k == IntegratorKind::Igi;
}

// Bounds of what render() accepts: the pixel count (a 16384x16384 image) and the samples per pixel.
constexpr uint64_t kMaxRenderPixels = uint64_t(1) << 28;
constexpr int kMaxSpp = 1 << 24;

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
  int tile_size = 16;
  // Instant global illumination (IntegratorKind::Igi, render/igi.h).
  int vpl_sets = 4;            // independent VPL sets; each camera sample gathers from one of them
  int light_paths = 64;        // light paths traced per set (each leaves a VPL at every non-specular hit)
  // Clamp of the geometry term |cos_x| |cos_y| / d^2 between a shading point and a VPL, relative to the scene:
  // G <= g_limit / R^2 with R the radius of the scene's bounding sphere (scale-invariant). Infinity: no clamp
  // (unbiased, spiky); small values remove the spikes near corners at the price of darker inter-reflections.
  float g_limit = 20;
  // Russian roulette on weak VPL paths: once a light path's throughput falls below vpl_roulette times what it
  // left the light with, it continues with probability (throughput / start) / vpl_roulette (reweighted, so
  // unbiased). 0 disables it (paths then end at max_depth or when they leave the scene).
  float vpl_roulette = 0.25f;
};

struct RenderStats {
  uint64_t camera_rays = 0, extension_rays = 0, shadow_rays = 0;
  uint64_t dropped_samples = 0;  // NaN or infinite radiance, never added to the film
  uint64_t samples_done = 0;     // camera samples that reached the film (or were dropped)
  double render_seconds = 0;
  bool interrupted = false;
  uint64_t rays() const { return camera_rays + extension_rays + shadow_rays; }
};

// Receives progress from worker threads; implementations must be thread-safe and cheap.
class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  virtual void update(uint64_t samples_done, uint64_t samples_total, uint64_t rays, double elapsed_seconds) = 0;
};

struct RenderOutput {
  Image image;
  RenderStats stats;
};

// Bytes render() allocates for an image of these settings (film and result), checked against the memory budget.
uint64_t render_memory_bytes(const RenderSettings& settings);

// Renders the scene as `camera` sees it (a Camera made for settings.width x settings.height). `cancel` (may be
// null) stops the render between tiles; the image then holds the samples done so far. Throws torte::Error for
// invalid settings, a film over the memory budget, or an image texture that fails to read while rendering
// (naming the file).
RenderOutput render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                    ProgressSink* progress = nullptr, const std::atomic<bool>* cancel = nullptr);

}  // namespace torte
