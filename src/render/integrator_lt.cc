#include "render/integrator_lt.h"

#include "render/shade_light.h"
#include "render/stage_hits.h"
#include "render/stage_light.h"
#include "render/stage_trace.h"
#include "render/tile_loop.h"
#include "render/wavefront.h"

namespace torte {

namespace {

// The light-path wavefront of one worker: start a light path per request, then per bounce trace, sort the hits
// by material type, shade each type (connections and next rays), trace the connections and splat them.
class LightTracer {
 public:
  template <MaterialType T>
  using Scratch = ShadeScratch<typename MaterialTraits<T>::Bsdf>;

  LightTracer(const Scene& scene, const Camera& camera, const Sampler& sampler, const TransportRules& rules)
      : scene_(scene), camera_(camera), sampler_(sampler), rules_(rules) {}

  void render(std::span<const SampleRequest> requests, const Film& film, SplatBuffer& splats, RenderStats& stats) {
    generate_light_rays(requests, scene_, sampler_, paths_, rays_);
    while (rays_.size() != 0) {
      trace_rays(scene_, rays_, hits_, false);
      stats.extension_rays += rays_.size();
      sort_hits(scene_, rules_, sampler_, 0.0f, rays_, hits_, paths_, queues_);
      next_.clear();
      connections_.clear();
      const ShadeContext ctx{scene_, rules_, sampler_, paths_, rays_, hits_, next_, no_shadows_};
      for_each_shaded_type([&](auto t) {
        shade_light_queue<t()>(ctx, camera_, queues_.queue(t()), std::get<int(t())>(scratch_), raster_,
                               connections_);
      });
      trace_camera_connections(scene_, connections_, film, splats, occluded_, stats);
      std::swap(rays_, next_);
    }
  }

 private:
  const Scene& scene_;
  const Camera& camera_;
  const Sampler& sampler_;
  TransportRules rules_;
  PathState paths_;
  RayQueue rays_, next_;
  HitQueue hits_;
  MaterialQueues queues_;
  ShadowQueue no_shadows_;  // the shading context's; light-path kernels queue camera connections instead
  CameraQueue connections_;
  std::vector<Vec2f> raster_;
  std::vector<uint8_t> occluded_;
  PerShadedType<Scratch> scratch_;
};

class LtDriver {
 public:
  struct Worker {
    Wavefront camera;  // emitters seen directly: camera rays of max_depth 0
    LightTracer light;
    bool light_paths;
    void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
      camera.render(requests, film, stats);
      if (light_paths) light.render(requests, film, splats, stats);
    }
  };
  LtDriver(const Scene& scene, const Camera& camera, const RenderSettings& settings)
      : scene_(scene), camera_(camera), settings_(settings), sampler_(settings.seed),
        lt_(LtSettings::from(settings)) {}
  void begin_pass(int, int) {}
  std::unique_ptr<Worker> make_worker() {
    return std::make_unique<Worker>(Worker{Wavefront(scene_, camera_, settings_, sampler_, lt_.camera_rules()),
                                           LightTracer(scene_, camera_, sampler_, lt_.light_rules()),
                                           lt_.max_depth > 0 && !scene_.lights.empty()});
  }
  void finish(RenderStats&) {}

 private:
  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& settings_;
  Sampler sampler_;
  LtSettings lt_;
};

}  // namespace

RenderOutput render_lt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                       ProgressSink* progress, const std::atomic<bool>* cancel) {
  LtDriver driver(scene, camera, settings);
  return run_tiles(scene, settings, driver, progress, cancel);
}

}  // namespace torte
