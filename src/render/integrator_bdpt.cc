#include "render/integrator_bdpt.h"

#include "core/error.h"
#include "light/light_emission.h"
#include "render/bdpt_connect.h"
#include "render/bdpt_subpath.h"
#include "render/bdpt_subpaths.h"
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
  BdptTracer(const Scene& scene, const Camera& camera, const RenderSettings& image, const Sampler& sampler,
             const BdptSettings& bdpt)
      : scene_(scene), camera_(camera), image_(image), bdpt_(bdpt), rules_(bdpt.rules()),
        connector_(scene, camera, sampler, {bdpt.max_depth, bdpt.only_s, bdpt.only_t}),
        subpaths_(scene, rules_, sampler) {}

  void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
    StageStats& st = stats.stages;
    clock_ = StageClock(st.enabled);
    clock_.start();
    subpaths_.start_light(requests, lpaths_, light_);
    clock_.lap(st[Stage::Camera], requests.size());
    // Light subpaths: their last vertex (depth max_depth - 1) only connects to the camera, so they stop there.
    if (bdpt_.max_depth > 0)
      subpaths_.advance(lpaths_, light_, TransportMode::Importance, kDimLightSubpathBase, 0.0f, bdpt_.max_depth,
                        false, stats, clock_);
    else
      subpaths_.drop_rays();
    subpaths_.start_camera(requests, camera_, image_, cpaths_, camera_store_);
    stats.camera_rays += requests.size();
    clock_.lap(st[Stage::Camera], requests.size());
    subpaths_.advance(cpaths_, camera_store_, TransportMode::Radiance, 0, camera_.spread_angle(),
                      bdpt_.max_depth + 1, true, stats, clock_);
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
  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& image_;
  BdptSettings bdpt_;
  TransportRules rules_;
  BdptConnector connector_;
  PathState lpaths_, cpaths_;
  BdptStore light_, camera_store_;
  BdptSubpaths subpaths_;
  ShadowQueue shadows_;
  CameraQueue splat_queue_;
  std::vector<uint8_t> occluded_;
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
