#include "render/integrator_bdpt.h"

#include "core/error.h"
#include "light/light_emission.h"
#include "render/bdpt_connect.h"
#include "render/bdpt_subpath.h"
#include "render/stage_camera.h"
#include "render/stage_film.h"
#include "render/stage_hits.h"
#include "render/stage_light.h"
#include "render/stage_trace.h"
#include "render/tile_loop.h"

namespace torte {

namespace {

// One worker's wavefront: per batch of requests, the light subpaths, then the camera subpaths (each advanced
// bounce by bounce through trace, sort and the per-type subpath kernels), then every connection, traced as
// two batches of shadow rays, then the film.
class BdptTracer {
 public:
  template <MaterialType T>
  using Scratch = ShadeScratch<typename MaterialTraits<T>::Bsdf>;

  BdptTracer(const Scene& scene, const Camera& camera, const RenderSettings& image, const Sampler& sampler,
             const BdptSettings& bdpt)
      : scene_(scene), camera_(camera), image_(image), sampler_(sampler), bdpt_(bdpt), rules_(bdpt.rules()),
        connector_(scene, camera, sampler, {bdpt.max_depth, bdpt.only_s, bdpt.only_t}) {}

  void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
    StageStats& st = stats.stages;
    clock_ = StageClock(st.enabled);
    clock_.start();
    start_light_subpaths(requests);
    clock_.lap(st[Stage::Camera], requests.size());
    // Light subpaths: their last vertex (depth max_depth - 1) only connects to the camera, so they stop there.
    if (bdpt_.max_depth > 0) advance(lpaths_, light_, TransportMode::Importance, kDimLightSubpathBase, 0.0f,
                                     bdpt_.max_depth, false, stats);
    start_camera_subpaths(requests);
    stats.camera_rays += requests.size();
    clock_.lap(st[Stage::Camera], requests.size());
    advance(cpaths_, camera_store_, TransportMode::Radiance, 0, camera_.spread_angle(), bdpt_.max_depth + 1, true,
            stats);
    shadows_.clear();
    splat_queue_.clear();
    for (uint32_t i = 0; i < uint32_t(requests.size()); ++i)
      connector_.connect(i, light_, camera_store_, cpaths_, shadows_, splat_queue_);
    clock_.lap(st[Stage::Connect], requests.size());
    trace_shadows(scene_, shadows_, cpaths_, occluded_, stats);
    trace_camera_connections(scene_, splat_queue_, film, splats, occluded_, stats);
    clock_.lap(st[Stage::Shadows], shadows_.size() + splat_queue_.size());
    accumulate_samples(cpaths_, film, stats);
    clock_.lap(st[Stage::Film], cpaths_.size());
  }

 private:
  // Light vertex 0 of every request and the first ray leaving it (generate_light_rays, drawing its light choice
  // from the light subpaths' own dimensions).
  void start_light_subpaths(std::span<const SampleRequest> requests) {
    light_.clear(requests.size());
    generate_light_rays(requests, scene_, sampler_, lpaths_, rays_, kDimLightSubpathBase,
                        [&](size_t i, int l, float pmf, const EmissionSample& es) {
                          BdptVertex v;
                          v.kind = BdptVertexKind::Light;
                          v.p = es.origin;
                          v.ng = es.normal;
                          v.light = l;
                          v.pdf_fwd = pmf * es.pdf_pos;
                          light_.push(v, uint32_t(i));
                          lpaths_.bsdf_pdf[i] = es.pdf_dir;
                        });
  }

  // Camera vertex 0 of every request and its camera ray (generate_camera_rays: filter and lens samples).
  void start_camera_subpaths(std::span<const SampleRequest> requests) {
    generate_camera_rays(requests, camera_, image_.filter, image_.width, image_.height, sampler_, cpaths_, rays_);
    camera_store_.clear(requests.size());
    for (size_t k = 0; k < rays_.size(); ++k) {
      const uint32_t i = rays_.path[k];
      BdptVertex v;
      v.kind = BdptVertexKind::Camera;
      v.p = rays_.origin(k);
      v.pdf_fwd = 1;
      camera_store_.push(v, i);
      float pdf_pos, pdf_dir;
      camera_.pdf_we(Ray{rays_.origin(k), rays_.dir(k)}, &pdf_pos, &pdf_dir);
      cpaths_.bsdf_pdf[i] = pdf_dir;  // the density of the first ray, for camera vertex 1's pdf_fwd
    }
  }

  // Advances the subpaths whose first rays are in rays_ until none goes on, keeping their vertices in `store`.
  void advance(PathState& ps, BdptStore& store, TransportMode mode, uint32_t dim_base, float spread,
               int depth_limit, bool camera_rays, RenderStats& stats) {
    StageStats& st = stats.stages;
    for (int bounce = 0; rays_.size() != 0; ++bounce) {
      const bool coherent = camera_rays && bounce == 0;  // a tile's camera rays, as Wavefront traces them
      trace_rays(scene_, rays_, hits_, coherent);
      if (!coherent) stats.extension_rays += rays_.size();
      clock_.lap(st[Stage::Trace], rays_.size());
      sort_hits(scene_, rules_, sampler_, spread, rays_, hits_, ps, queues_, dim_base);
      record_subpath_hits(scene_, rays_, hits_, ps, mode == TransportMode::Importance, store);
      clock_.lap(st[Stage::Hits], queues_.slots.size());
      next_.clear();
      const ShadeContext ctx{scene_, rules_, sampler_, ps, rays_, hits_, next_, no_shadows_};
      for_each_shaded_type([&](auto t) {
        const std::span<const uint32_t> queue = queues_.queue(t());
        shade_subpath_queue<t()>(ctx, queue, std::get<int(t())>(scratch_), store, mode, dim_base, depth_limit);
        if (!queue.empty()) clock_.lap(st.shade[int(t())], queue.size());
      });
      std::swap(rays_, next_);
    }
  }

  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& image_;
  const Sampler& sampler_;
  BdptSettings bdpt_;
  TransportRules rules_;
  BdptConnector connector_;
  PathState lpaths_, cpaths_;
  BdptStore light_, camera_store_;
  RayQueue rays_, next_;
  HitQueue hits_;
  MaterialQueues queues_;
  ShadowQueue no_shadows_;  // the shading context's; subpath kernels queue no shadow rays
  ShadowQueue shadows_;
  CameraQueue splat_queue_;
  std::vector<uint8_t> occluded_;
  PerShadedType<Scratch> scratch_;
  StageClock clock_;
};

class BdptDriver {
 public:
  struct Worker {
    BdptTracer tracer;
    void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
      tracer.render(requests, film, stats, splats);
    }
  };
  BdptDriver(const Scene& scene, const Camera& camera, const RenderSettings& settings, const BdptSettings& bdpt)
      : scene_(scene), camera_(camera), settings_(settings), sampler_(settings.seed), bdpt_(bdpt) {}
  void begin_pass(int, int) {}
  std::unique_ptr<Worker> make_worker() {
    return std::make_unique<Worker>(Worker{BdptTracer(scene_, camera_, settings_, sampler_, bdpt_)});
  }
  void finish(RenderStats&) {}

 private:
  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& settings_;
  Sampler sampler_;
  BdptSettings bdpt_;
};

}  // namespace

std::string bdpt_problem(const Scene& scene, const Camera& camera) {
  if (const std::string why = camera.connect_problem(); !why.empty()) return why;
  if (camera.desc().kind != CameraKind::Perspective)
    return "needs a perspective camera (its light subpaths connect to the lens with the perspective density)";
  for (const Light& l : scene.lights)
    if (l.kind != LightKind::Area && l.kind != LightKind::Point && l.kind != LightKind::Spot)
      return "does not support " + light_name(l) +
             " (area, point and spot lights only; use integrator \"path\" or \"lt\" for this scene)";
  return "";
}

RenderOutput render_bdpt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         const BdptSettings& bdpt, ProgressSink* progress, const std::atomic<bool>* cancel) {
  if (const std::string why = bdpt_problem(scene, camera); !why.empty()) throw Error("integrator 'bdpt': " + why);
  BdptDriver driver(scene, camera, settings, bdpt);
  return run_tiles(scene, settings, driver, progress, cancel);
}

RenderOutput render_bdpt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         ProgressSink* progress, const std::atomic<bool>* cancel) {
  return render_bdpt(scene, camera, settings, BdptSettings::from(settings), progress, cancel);
}

}  // namespace torte
