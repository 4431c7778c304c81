#include "render/stage_camera.h"

#include <vector>

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
    paths.pixel[i] = requests[i].pixel;
    paths.sample[i] = requests[i].sample;
  }
  // The filter's (and the lens') numbers of the whole batch at once, in vector lanes (Sampler::get_batch).
  // Scratch of this thread, reused by its later batches.
  thread_local std::vector<uint32_t> dim, scratch;
  thread_local std::vector<float> filter_u, filter_v, lens_u, lens_v;
  dim.assign(n, kDimFilter);
  scratch.resize(3 * n);
  filter_u.resize(n), filter_v.resize(n);
  sampler.get_batch(n, paths.pixel.data(), paths.sample.data(), dim.data(), filter_u.data(), filter_v.data(),
                    scratch.data());
  if (lens) {
    dim.assign(n, kDimLens);
    lens_u.resize(n), lens_v.resize(n);
    sampler.get_batch(n, paths.pixel.data(), paths.sample.data(), dim.data(), lens_u.data(), lens_v.data(),
                      scratch.data());
  }
  for (size_t i = 0; i < n; ++i) {
    const uint32_t pixel = paths.pixel[i];
    const Filter::Sample fs = filter.sample(Vec2f(filter_u[i], filter_v[i]));
    const Vec2f raster = filter_raster_position(int(pixel % uint32_t(width)), int(pixel / uint32_t(width)),
                                                fs.offset, width, height);
    const Ray ray = lens ? camera.generate_ray(raster, Vec2f(lens_u[i], lens_v[i])) : camera.generate_ray(raster);
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
