// The public entry point: render(scene, camera, settings) runs the integrator settings.integrator asks for
// (render/integrator_path.h, integrator_direct.h, integrator_igi.h, integrator_lt.h), each a small driver over
// the shared stages of render/wavefront.h, over progressive passes of image tiles (render/tile_loop.h). Every
// pixel belongs to one tile and each camera sample only contributes to its own pixel (filter importance
// sampling); light tracing's splats go to one buffer per tile, merged in tile order. So the image is bitwise
// identical for any thread count or schedule.
#pragma once
#include <atomic>
#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "film/image.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace torte {

// Receives progress from worker threads; implementations must be thread-safe and cheap.
class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  virtual void update(uint64_t samples_done, uint64_t samples_total, uint64_t rays, double elapsed_seconds) = 0;
};

struct RenderOutput {
  Image image;
  RenderStats stats;
  std::vector<uint32_t> pixel_spp;  // samples each pixel took, with adaptive sampling (noise_threshold); else empty
  // With RenderSettings::pixel_variance: the variance of each pixel's mean luminance (Film::mean_variance); else
  // empty.
  std::vector<float> variance;
};

/// Bytes render() allocates for an image of these settings (film and result), checked against the memory budget.
uint64_t render_memory_bytes(const RenderSettings& settings);

/// Renders `camera`'s view of the scene; `camera` must be made for settings.width x settings.height. `cancel`
/// (may be null) stops the render between tiles; the image then holds the samples done so far. Throws
/// torte::Error for invalid settings, a film over the memory budget, or an image texture that fails to read
/// while rendering (naming the file).
RenderOutput render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                    ProgressSink* progress = nullptr, const std::atomic<bool>* cancel = nullptr);

}  // namespace torte
