// Stage: camera rays. Starts one path per requested camera sample and writes its first ray to the ray queue,
// in request order (neighbouring pixels next to each other: the trace stage packets them).
#pragma once
#include <cstdint>
#include <span>

#include "camera/camera.h"
#include "core/sampler.h"
#include "film/filter.h"
#include "render/path_state.h"

namespace torte {

struct SampleRequest {
  uint32_t pixel;   // linear index
  uint32_t sample;  // index within the pixel
};

/// Resizes `paths` to the requests and fills `rays` (cleared first) with their camera rays.
void generate_camera_rays(std::span<const SampleRequest> requests, const Camera& camera, const Filter& filter,
                          int width, int height, const Sampler& sampler, PathState& paths, RayQueue& rays);

}  // namespace torte
