#include "render/integrator_path.h"

#include "render/tile_loop.h"
#include "render/wavefront.h"

namespace torte {

namespace {

class CameraPathDriver {
 public:
  struct Worker {
    Wavefront wavefront;
    void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats) {
      wavefront.render(requests, film, stats);
    }
  };
  CameraPathDriver(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                   const TransportRules& rules)
      : scene_(scene), camera_(camera), settings_(settings), rules_(rules), sampler_(settings.seed) {}
  void begin_pass(int, int) {}
  std::unique_ptr<Worker> make_worker() {
    return std::make_unique<Worker>(Worker{Wavefront(scene_, camera_, settings_, sampler_, rules_)});
  }
  void finish(RenderStats&) {}

 private:
  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& settings_;
  TransportRules rules_;
  Sampler sampler_;
};

}  // namespace

RenderOutput render_camera_paths(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                                 const TransportRules& rules, ProgressSink* progress,
                                 const std::atomic<bool>* cancel) {
  CameraPathDriver driver(scene, camera, settings, rules);
  return run_tiles(scene, settings, driver, progress, cancel);
}

RenderOutput render_path(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         ProgressSink* progress, const std::atomic<bool>* cancel) {
  return render_camera_paths(scene, camera, settings, PathSettings::from(settings).rules(), progress, cancel);
}

}  // namespace torte
