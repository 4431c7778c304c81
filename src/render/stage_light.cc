#include "render/stage_light.h"

#include "light/light_emission.h"
#include "render/shade.h"

namespace torte {

void generate_light_rays(std::span<const SampleRequest> requests, const Scene& scene, const Sampler& sampler,
                         PathState& paths, RayQueue& rays) {
  const size_t n = requests.size();
  paths.resize(n);
  rays.clear();
  for (size_t i = 0; i < n; ++i) {
    const SampleRequest& r = requests[i];
    paths.pixel[i] = r.pixel;
    paths.sample[i] = r.sample;
    paths.radiance[i] = Rgb(0);
    paths.bsdf_pdf[i] = 0;
    paths.depth[i] = 0;
    paths.flags[i] = 0;
    paths.eta_scale[i] = 1;
    paths.footprint[i] = 0;
    paths.beta[i] = Rgb(0);
    paths.filter_weight[i] = 0;
    if (scene.lights.empty()) continue;
    float pmf, uc;
    const int l = scene.light_selection.sample_discrete(
        sampler.get_1d(r.pixel, r.sample, bounce_dim(0, kDimLightSelect)), &pmf, &uc);
    if (!(pmf > 0)) continue;
    EmissionSample es;
    if (!sample_emission(scene, scene.lights[size_t(l)], sampler.get_2d(r.pixel, r.sample, kDimEmitPosition),
                         sampler.get_2d(r.pixel, r.sample, kDimEmitDirection), uc, &es))
      continue;
    const Rgb beta = es.weight / pmf;
    const float scale = beta.max_component();
    if (!(scale > 0) || !beta.is_finite()) continue;
    paths.beta[i] = beta / scale;
    paths.filter_weight[i] = scale;
    const Vec3f o = length_squared(es.normal) > 0 ? offset_origin(es.origin, es.normal, es.dir) : es.origin;
    rays.push(o, es.dir, kInfinity, uint32_t(i));
  }
}

void trace_camera_connections(const Scene& scene, const CameraQueue& connections, const Film& film,
                              SplatBuffer& splats, std::vector<uint8_t>& occluded, RenderStats& stats) {
  const size_t n = connections.size();
  if (n == 0) return;
  occluded.resize(n);
  scene.occluded(connections.soa(), n, occluded.data(), false);
  for (size_t k = 0; k < n; ++k)
    if (!occluded[k] && !film.splat(splats, connections.raster[k], connections.contribution[k]))
      ++stats.dropped_samples;  // only a NaN or infinite value: connections land inside the image
  stats.shadow_rays += n;
}

}  // namespace torte
