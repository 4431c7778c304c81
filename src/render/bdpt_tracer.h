// The BDPT sample as a reusable piece (render/integrator_bdpt.h describes the algorithm): a worker's wavefront
// that traces one camera and one light subpath per sample request and joins them in every way. `bdpt` adds the
// results to the film; `mlt` (render/integrator_mlt.h) takes them as a list of contributions to weigh.
#pragma once
#include <span>
#include <vector>

#include "light/light_emission.h"
#include "render/bdpt_connect.h"
#include "render/bdpt_subpath.h"
#include "render/bdpt_subpaths.h"
#include "render/integrator_bdpt.h"
#include "render/stage_camera.h"
#include "render/stage_film.h"
#include "render/stage_hits.h"
#include "render/stage_light.h"
#include "render/stage_trace.h"

namespace torte {

/// What one sample (request `request` of a wavefront) adds to pixel `pixel`.
struct SampleContribution {
  uint32_t request;
  uint32_t pixel;
  Rgb value;
};

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

  /// One BDPT sample per request: the camera subpaths' radiance goes to `film`, their connections to the lens to
  /// `splats`.
  void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
    trace(requests, stats);
    StageStats& st = stats.stages;
    trace_camera_connections(scene_, splat_queue_, film, splats, occluded_, stats);
    clock_.lap(st[Stage::Shadows], shadows_.size() + splat_queue_.size());
    accumulate_samples(cpaths_, film, stats);
    clock_.lap(st[Stage::Film], cpaths_.size());
  }

  /// One BDPT sample per request, its contributions appended to `out` instead of added to a film (Metropolis
  /// light transport weighs each sample's before splatting): the camera subpath's radiance at its pixel (times
  /// its filter weight) and each unoccluded connection to the lens at its raster position's pixel.
  void contributions(std::span<const SampleRequest> requests, int width, int height, RenderStats& stats,
                     std::vector<SampleContribution>& out) {
    trace(requests, stats);
    const size_t n = splat_queue_.size();
    if (n > 0) {
      occluded_.resize(n);
      scene_.occluded(splat_queue_.soa(), n, occluded_.data(), false);
      stats.shadow_rays += n;
    }
    for (size_t i = 0; i < cpaths_.size(); ++i) {
      const Rgb L = cpaths_.radiance[i] * cpaths_.filter_weight[i];
      if (!L.is_finite()) {
        ++stats.dropped_samples;
      } else if (!L.is_black()) {
        out.push_back({uint32_t(i), cpaths_.pixel[i], L});
      }
    }
    for (size_t k = 0; k < n; ++k) {
      const Vec2f r = splat_queue_.raster[k];
      const Rgb& c = splat_queue_.contribution[k];
      if (occluded_[k] || c.is_black()) continue;
      if (!(r.x >= 0 && r.y >= 0 && r.x < float(width) && r.y < float(height)) || !c.is_finite()) {
        ++stats.dropped_samples;
        continue;
      }
      out.push_back({splat_queue_.path[k], uint32_t(int(r.y)) * uint32_t(width) + uint32_t(int(r.x)), c});
    }
  }

 private:
  // The subpaths of every request, their connections between surface vertices traced and added to the camera
  // paths' radiance; the connections to the lens queued in splat_queue_.
  void trace(std::span<const SampleRequest> requests, RenderStats& stats) {
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
  }

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

}  // namespace torte
