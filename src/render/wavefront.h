// The wavefront loop shared by the camera-path integrators: generate camera rays, then per bounce trace, sort
// the hits by material type, add the light the rays found (escaped rays, emitters), shade per material type,
// trace the shadow rays; finally add the paths to the film. Each stage call is one lap of the stage clock
// (render/stage_stats.h). An integrator is a Hook (static: no virtual call per ray or hit) that may look at each
// shaded queue (IGI records the hits that gather from its VPLs) and act after each bounce's shadow rays.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "camera/camera.h"
#include "core/sampler.h"
#include "film/film.h"
#include "material/material_types.h"
#include "render/path_state.h"
#include "render/render_settings.h"
#include "render/shade.h"
#include "render/stage_camera.h"
#include "render/stage_emission.h"
#include "render/stage_film.h"
#include "render/stage_hits.h"
#include "render/stage_stats.h"
#include "render/stage_trace.h"

namespace torte {

/// The Hook of integrators that add nothing to the shared stages (path, direct).
struct NoWavefrontHook {
  template <class Tag, class Scratch>
  void shaded(Tag, const Scratch&, std::span<const uint32_t>) {}
  template <class W>
  void after_bounce(W&, RenderStats&) {}
};

class Wavefront {
 public:
  template <MaterialType T>
  using Scratch = ShadeScratch<typename MaterialTraits<T>::Bsdf>;

  /// `camera` must be made for the image size of `image`; all references must outlive the wavefront.
  Wavefront(const Scene& scene, const Camera& camera, const RenderSettings& image, const Sampler& sampler,
            const TransportRules& rules)
      : scene_(scene), camera_(camera), image_(image), sampler_(sampler), rules_(rules) {
    rules_.light_sampler = image.light_sampler;
  }

  /// Renders the requested camera samples and adds them to the film; counts rays and dropped samples.
  template <class Hook = NoWavefrontHook>
  void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, Hook&& hook = {});

  // For hooks: the state of the bounce being rendered.
  const Scene& scene() const { return scene_; }
  PathState& paths() { return paths_; }
  const RayQueue& rays() const { return rays_; }
  const HitQueue& hits() const { return hits_; }
  template <MaterialType T>
  const Scratch<T>& scratch() const { return std::get<int(T)>(scratch_); }
  std::vector<uint8_t>& occluded_scratch() { return occluded_; }
  /// The stage clock of the batch being rendered: a hook laps its own stages into RenderStats::stages with it.
  StageClock& clock() { return clock_; }

 private:
  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& image_;
  const Sampler& sampler_;
  TransportRules rules_;
  PathState paths_;
  RayQueue rays_, next_;  // this bounce's rays, the next bounce's (swapped after each bounce)
  HitQueue hits_;
  MaterialQueues queues_;
  ShadowQueue shadows_;
  std::vector<uint8_t> occluded_;
  PerShadedType<Scratch> scratch_;  // shading scratch, one per shaded material type
  StageClock clock_;
};

template <class Hook>
void Wavefront::render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, Hook&& hook) {
  StageStats& st = stats.stages;
  clock_ = StageClock(st.enabled);
  clock_.start();
  generate_camera_rays(requests, camera_, image_.filter, image_.width, image_.height, sampler_, paths_, rays_);
  stats.camera_rays += requests.size();
  clock_.lap(st[Stage::Camera], requests.size());
  const float spread = camera_.spread_angle();
  for (int bounce = 0; rays_.size() != 0; ++bounce) {
    // Camera rays of a tile come pixel by pixel, neighbours next to each other: trace them as packets. Bounced
    // rays are incoherent and go one at a time. Camera rays were counted when generated.
    trace_rays(scene_, rays_, hits_, bounce == 0);
    if (bounce != 0) stats.extension_rays += rays_.size();
    clock_.lap(st[Stage::Trace], rays_.size());
    sort_hits(scene_, rules_, sampler_, spread, rays_, hits_, paths_, queues_);
    clock_.lap(st[Stage::Hits], queues_.slots.size());
    add_emission(scene_, rules_, rays_, hits_, paths_);
    clock_.lap(st[Stage::Emission], rays_.size());
    next_.clear();
    shadows_.clear();
    const ShadeContext ctx{scene_, rules_, sampler_, paths_, rays_, hits_, next_, shadows_};
    for_each_shaded_type([&](auto t) {
      const std::span<const uint32_t> queue = queues_.queue(t());
      // Empty queues still run (a hook clears what it recorded) but are not laps: their nanoseconds go to the
      // next stage, and only types that were hit get a line.
      shade_queue<t()>(ctx, queue, std::get<int(t())>(scratch_),
                       [&](const auto& sc, std::span<const uint32_t> q) { hook.shaded(t, sc, q); });
      if (!queue.empty()) clock_.lap(st.shade[int(t())], queue.size());
    });
    trace_shadows(scene_, shadows_, paths_, occluded_, stats);
    clock_.lap(st[Stage::Shadows], shadows_.size());
    hook.after_bounce(*this, stats);
    std::swap(rays_, next_);
  }
  accumulate_samples(paths_, film, stats);
  clock_.lap(st[Stage::Film], paths_.size());
}

}  // namespace torte
