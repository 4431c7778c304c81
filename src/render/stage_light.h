// Stages of light paths (light tracing now, BDPT's light subpaths later): start one light path per request by
// emission sampling, and trace the batch of connections to the camera, splatting the unoccluded ones.
// A light path is a PathState entry like a camera path: it draws its numbers from the sampler under its
// request's (pixel, sample), so it is as deterministic, and the shared trace/sort/shade stages advance it.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/ray.h"
#include "core/sampler.h"
#include "film/film.h"
#include "light/light_emission.h"
#include "render/path_state.h"
#include "render/shade.h"
#include "render/stage_camera.h"
#include "scene/scene.h"

namespace torte {

// Sample dimensions of a light path's start, above every per-bounce and per-light dimension and the camera's
// lens dimension (1 << 30), so a request's camera sample and light path draw different numbers. The light's
// selection uses bounce 0's kDimLightSelect, which light-path vertices never read (they do no light sampling).
constexpr uint32_t kDimEmitPosition = (1u << 30) + 1;
constexpr uint32_t kDimEmitDirection = (1u << 30) + 2;

/// The on_emit hook of generate_light_rays for light paths that need none.
struct NoEmitHook {
  void operator()(size_t, int, float, const EmissionSample&) const {}
};

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
/// first; a request whose emission sample carries nothing gets no ray). The light is chosen by power, from the
/// sampler dimension `select_dim_base + bounce_dim(0, kDimLightSelect)`. beta holds the emitted throughput
/// divided by its largest component, which goes to filter_weight (so Russian roulette sees a throughput that
/// starts at 1): the path carries filter_weight * beta. `on_emit(i, light, pmf, es)` sees every path that gets
/// a ray, before its ray is queued (BDPT records the light vertex there).
template <class OnEmit = NoEmitHook>
void generate_light_rays(std::span<const SampleRequest> requests, const Scene& scene, const Sampler& sampler,
                         PathState& paths, RayQueue& rays, uint32_t select_dim_base = 0, OnEmit&& on_emit = {}) {
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
        sampler.get_1d(r.pixel, r.sample, select_dim_base + bounce_dim(0, kDimLightSelect)), &pmf, &uc);
    if (!(pmf > 0)) continue;
    EmissionSample es;
    if (!sample_emission(scene, scene.lights[size_t(l)], sampler.get_2d(r.pixel, r.sample, kDimEmitPosition),
                         sampler.get_2d(r.pixel, r.sample, kDimEmitDirection), uc, &es))
      continue;
    const Rgb beta = es.weight / pmf;
    const float scale = beta.max_component();
    if (!(scale > 0) || !beta.is_finite()) continue;
    on_emit(i, l, pmf, es);
    paths.beta[i] = beta / scale;
    paths.filter_weight[i] = scale;
    const Vec3f o = length_squared(es.normal) > 0 ? offset_origin(es.origin, es.normal, es.dir) : es.origin;
    rays.push(o, es.dir, kInfinity, uint32_t(i));
  }
}


/// Traces the connections and splats the unoccluded ones into `splats`, in queue order. `occluded` is
/// scratch. Counts the rays in stats.shadow_rays and non-finite splats (dropped) in stats.dropped_samples.
void trace_camera_connections(const Scene& scene, const CameraQueue& connections, const Film& film,
                              SplatBuffer& splats, std::vector<uint8_t>& occluded, RenderStats& stats);

}  // namespace torte
