// Stages of light paths (light tracing now, BDPT's light subpaths later): start one light path per request by
// emission sampling, and trace the batch of connections to the camera, splatting the unoccluded ones.
// A light path is a PathState entry like a camera path: it draws its numbers from the sampler under its
// request's (pixel, sample), so it is as deterministic, and the shared trace/sort/shade stages advance it.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/sampler.h"
#include "film/film.h"
#include "render/path_state.h"
#include "render/stage_camera.h"

namespace torte {

// Sample dimensions of a light path's start, above every per-bounce and per-light dimension and the camera's
// lens dimension (1 << 30), so a request's camera sample and light path draw different numbers. The light's
// selection uses bounce 0's kDimLightSelect, which light-path vertices never read (they do no light sampling).
constexpr uint32_t kDimEmitPosition = (1u << 30) + 1;
constexpr uint32_t kDimEmitDirection = (1u << 30) + 2;

/// Connections to the camera: shadow rays towards the lens, each with the value it splats and where.
struct CameraQueue : ShadowQueue {
  std::vector<Vec2f> raster;
  void push(Vec3f o, Vec3f d, float t, Rgb c, uint32_t p, Vec2f r) {
    const size_t k = size();
    ShadowQueue::push(o, d, t, c, p);
    if (raster.size() < path.size()) raster.resize(path.size());
    raster[k] = r;
  }
};

/// Resizes `paths` to the requests and writes the first ray of a light path for each into `rays` (cleared
/// first; a request whose emission sample carries nothing gets no ray). The light is chosen by power. beta
/// holds the emitted throughput divided by its largest component, which goes to filter_weight (so Russian
/// roulette sees a throughput that starts at 1): the path carries filter_weight * beta.
void generate_light_rays(std::span<const SampleRequest> requests, const Scene& scene, const Sampler& sampler,
                         PathState& paths, RayQueue& rays);

/// Traces the connections and splats the unoccluded ones into `splats`, in queue order. `occluded` is
/// scratch. Counts the rays in stats.shadow_rays and non-finite splats (dropped) in stats.dropped_samples.
void trace_camera_connections(const Scene& scene, const CameraQueue& connections, const Film& film,
                              SplatBuffer& splats, std::vector<uint8_t>& occluded, RenderStats& stats);

}  // namespace torte
