#include "render/integrator_igi.h"

#include "render/integrator_direct.h"
#include "render/tile_loop.h"
#include "render/vpl.h"
#include "render/wavefront.h"

namespace torte {

namespace {

// The wavefront hook: records the hits that gather (after each type's shading), gathers after the bounce's
// direct-light shadow rays, tracing VPL shadow rays in coherent batches.
class IgiHook {
 public:
  IgiHook(const VplStore& vpls, uint64_t seed) : vpls_(&vpls), seed_(seed) {}
  void bind(Wavefront& wavefront) { wavefront_ = &wavefront; }

  template <class Tag, class Scratch>
  void shaded(Tag t, const Scratch& sc, std::span<const uint32_t> queue) {
    std::vector<VplHit>& out = hits_[int(t())];
    out.clear();
    const PathState& ps = wavefront_->paths();
    const RayQueue& rays = wavefront_->rays();
    for (size_t k = 0; k < queue.size(); ++k) {
      if (!sc.bsdf[k].has_non_specular()) continue;
      const uint32_t i = rays.path[queue[k]];
      out.push_back({uint32_t(k), queue[k], i, ps.beta[i]});
    }
  }

  void after_bounce(Wavefront& w, RenderStats& stats) {
    shadows_.clear();
    StageClock& clock = w.clock();
    auto flush = [&] {
      if (shadows_.size() == 0) return;
      clock.lap(stats.stages[Stage::VplGather], shadows_.size());  // the queueing since the last lap
      trace_shadows(w.scene(), shadows_, w.paths(), w.occluded_scratch(), stats, true);  // runs towards one VPL
      clock.lap(stats.stages[Stage::Shadows], shadows_.size());
      shadows_.clear();
    };
    for_each_shaded_type([&](auto t) {
      gather_vpls<t()>(*vpls_, w.scratch<t()>(), hits_[int(t())], w.paths(), w.hits(), seed_, shadows_, order_,
                       begin_, flush);
    });
    flush();
    clock.lap(stats.stages[Stage::VplGather], 0);  // what followed the last flush
  }

 private:
  const VplStore* vpls_;  // the driver's, replaced before every pass
  uint64_t seed_;
  Wavefront* wavefront_ = nullptr;
  std::vector<VplHit> hits_[kShadedMaterialTypeCount];
  ShadowQueue shadows_;
  std::vector<uint32_t> order_, begin_;
};

class IgiDriver {
 public:
  struct Worker {
    Wavefront wavefront;
    IgiHook hook;
    void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats) {
      hook.bind(wavefront);
      wavefront.render(requests, film, stats, hook);
    }
  };
  IgiDriver(const Scene& scene, const Camera& camera, const RenderSettings& settings)
      : scene_(scene), camera_(camera), settings_(settings), sampler_(settings.seed) {}

  // The VPL families of the pass's sample indices, drawn afresh (render/vpl.h).
  void begin_pass(int first_sample, int pass_spp) {
    vpls_ = generate_vpls(scene_, settings_, uint32_t(first_sample), pass_spp);
    light_rays_ += vpls_.light_rays;
    vpl_pass_.add(vpls_.profile);
  }
  std::unique_ptr<Worker> make_worker() {
    const TransportRules rules = DirectSettings::from(settings_).rules();
    return std::make_unique<Worker>(Worker{Wavefront(scene_, camera_, settings_, sampler_, rules),
                                           IgiHook(vpls_, settings_.seed)});
  }
  void finish(RenderStats& stats) {
    stats.extension_rays += light_rays_;  // IGI's light paths
    stats.stages[Stage::VplPass].add(vpl_pass_);
  }

 private:
  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& settings_;
  Sampler sampler_;
  VplStore vpls_;
  uint64_t light_rays_ = 0;
  StageTime vpl_pass_;  // the passes' VplStore::profile
};

}  // namespace

RenderOutput render_igi(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        ProgressSink* progress, const std::atomic<bool>* cancel) {
  IgiDriver driver(scene, camera, settings);
  return run_tiles(scene, settings, driver, progress, cancel);
}

}  // namespace torte
