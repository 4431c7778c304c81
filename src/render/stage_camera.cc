#include "render/stage_camera.h"

#include "render/shade.h"

namespace torte {

namespace {
// Thin-lens sample dimension: above every per-bounce and per-light dimension (kDimAllLightsBase + depth * 4096 +
// light stays below 2^29 for any uint16 depth), so it never collides with them.
constexpr uint32_t kDimLens = 1u << 30;
}  // namespace

void generate_camera_rays(std::span<const SampleRequest> requests, const Camera& camera, const Filter& filter,
                          int width, int height, const Sampler& sampler, PathState& paths, RayQueue& rays) {
  const size_t n = requests.size();
  paths.resize(n);
  rays.clear();
  const bool lens = camera.has_lens();
  const float footprint = camera.footprint_at_origin();
  for (size_t i = 0; i < n; ++i) {
    const SampleRequest& r = requests[i];
    const Filter::Sample fs = filter.sample(sampler.get_2d(r.pixel, r.sample, kDimFilter));
    const Vec2f raster = filter_raster_position(int(r.pixel % uint32_t(width)), int(r.pixel / uint32_t(width)),
                                                fs.offset, width, height);
    const Ray ray = lens ? camera.generate_ray(raster, sampler.get_2d(r.pixel, r.sample, kDimLens))
                         : camera.generate_ray(raster);
    paths.pixel[i] = r.pixel;
    paths.sample[i] = r.sample;
    paths.filter_weight[i] = fs.weight;
    paths.beta[i] = Rgb(1);
    paths.radiance[i] = Rgb(0);
    paths.bsdf_pdf[i] = 0;
    paths.depth[i] = 0;
    paths.flags[i] = 0;
    paths.eta_scale[i] = 1;
    paths.footprint[i] = footprint;
    rays.push(ray.o, ray.d, kInfinity, uint32_t(i));
  }
}

}  // namespace torte
