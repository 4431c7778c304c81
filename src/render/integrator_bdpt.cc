#include "render/integrator_bdpt.h"

#include "core/error.h"
#include "render/bdpt_tracer.h"
#include "render/tile_loop.h"

namespace torte {

namespace {

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
