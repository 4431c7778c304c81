// The subpath stages bdpt and vcm share: light and camera subpaths started into a BdptStore, then advanced bounce by
// bounce (trace, sort by material type, record the vertices, the per-type subpath kernels) until none goes on.
// Each worker's tracer owns one; the connections and merges that read the stores are the integrators' own.
#pragma once
#include <span>

#include "camera/camera.h"
#include "core/sampler.h"
#include "render/bdpt_subpath.h"
#include "render/stage_camera.h"
#include "render/stage_hits.h"
#include "render/stage_light.h"
#include "render/stage_stats.h"
#include "render/stage_trace.h"

namespace torte {

class BdptSubpaths {
 public:
  /// Holds its own copy of `rules`: tracers are moved into their workers after construction.
  BdptSubpaths(const Scene& scene, const TransportRules& rules, const Sampler& sampler)
      : scene_(scene), rules_(rules), sampler_(sampler) {}

  /// Light vertex 0 of every request into `store` and the first ray leaving it (generate_light_rays, its light
  /// choice drawn from the light subpaths' own dimensions).
  void start_light(std::span<const SampleRequest> requests, PathState& ps, BdptStore& store) {
    store.clear(requests.size());
    generate_light_rays(requests, scene_, sampler_, ps, rays_, kDimLightSubpathBase,
                        [&](size_t i, int l, float pmf, const EmissionSample& es) {
                          BdptVertex v;
                          v.kind = BdptVertexKind::Light;
                          v.p = es.origin;
                          v.ng = es.normal;
                          v.light = l;
                          v.pdf_fwd = pmf * es.pdf_pos;
                          store.push(v, uint32_t(i));
                          ps.bsdf_pdf[i] = es.pdf_dir;
                        });
  }

  /// Camera vertex 0 of every request into `store` and its camera ray (generate_camera_rays: filter and lens).
  void start_camera(std::span<const SampleRequest> requests, const Camera& camera, const RenderSettings& image,
                    PathState& ps, BdptStore& store) {
    generate_camera_rays(requests, camera, image.filter, image.width, image.height, sampler_, ps, rays_);
    store.clear(requests.size());
    for (size_t k = 0; k < rays_.size(); ++k) {
      const uint32_t i = rays_.path[k];
      BdptVertex v;
      v.kind = BdptVertexKind::Camera;
      v.p = rays_.origin(k);
      v.pdf_fwd = 1;
      store.push(v, i);
      float pdf_pos, pdf_dir;
      camera.pdf_we(Ray{rays_.origin(k), rays_.dir(k)}, &pdf_pos, &pdf_dir);
      ps.bsdf_pdf[i] = pdf_dir;  // the density of the first ray, for camera vertex 1's pdf_fwd
    }
  }

  /// Advances the subpaths whose first rays the last start_* queued until none goes on, keeping their vertices
  /// in `store`; `depth_limit` bounds the vertices a subpath keeps, `camera_rays` traces the first bounce as a
  /// tile's coherent camera rays.
  void advance(PathState& ps, BdptStore& store, TransportMode mode, uint32_t dim_base, float spread,
               int depth_limit, bool camera_rays, RenderStats& stats, StageClock& clock) {
    StageStats& st = stats.stages;
    for (int bounce = 0; rays_.size() != 0; ++bounce) {
      const bool coherent = camera_rays && bounce == 0;  // a tile's camera rays, as Wavefront traces them
      trace_rays(scene_, rays_, hits_, coherent);
      if (!coherent) stats.extension_rays += rays_.size();
      clock.lap(st[Stage::Trace], rays_.size());
      sort_hits(scene_, rules_, sampler_, spread, rays_, hits_, ps, queues_, dim_base);
      record_subpath_hits(scene_, rays_, hits_, ps, mode == TransportMode::Importance, store);
      clock.lap(st[Stage::Hits], queues_.slots.size());
      next_.clear();
      const ShadeContext ctx{scene_, rules_, sampler_, ps, rays_, hits_, next_, no_shadows_};
      for_each_shaded_type([&](auto t) {
        const std::span<const uint32_t> queue = queues_.queue(t());
        shade_subpath_queue<t()>(ctx, queue, std::get<int(t())>(scratch_), store, mode, dim_base, depth_limit);
        if (!queue.empty()) clock.lap(st.shade[int(t())], queue.size());
      });
      std::swap(rays_, next_);
    }
  }

  /// Drops the rays a start_* queued (a subpath that stops at its first vertex).
  void drop_rays() { rays_.clear(); }

 private:
  template <MaterialType T>
  using Scratch = ShadeScratch<typename MaterialTraits<T>::Bsdf>;

  const Scene& scene_;
  TransportRules rules_;
  const Sampler& sampler_;
  RayQueue rays_, next_;
  HitQueue hits_;
  MaterialQueues queues_;
  ShadowQueue no_shadows_;  // the shading context's; subpath kernels queue no shadow rays
  PerShadedType<Scratch> scratch_;
};

}  // namespace torte
