// BDPT's connection stage (render/integrator_bdpt.h): for the camera and light subpaths of one sample, every
// strategy (s light vertices, t camera vertices) with s + t - 2 <= max_depth, each weighted by the power
// heuristic over all strategies that could have made the same path. Connections are not traced here: s = 0
// adds to the path at once (no visibility to test), t = 1 queues a shadow ray towards the lens carrying a splat,
// the others queue a shadow ray carrying radiance to the camera path; the caller traces both queues as batches.
#pragma once
#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "core/sampler.h"
#include "render/bdpt_subpath.h"
#include "render/stage_light.h"

namespace torte {

/// What the connections read, fixed for a render.
struct BdptConnectRules {
  int max_depth = 64;
  // Debugging and tests: when only_s >= 0, only strategy (only_s, only_t) contributes (still MIS-weighted), so
  // that the strategies' images can be summed and compared with the full estimate.
  int only_s = -1, only_t = -1;
  // VCM (render/integrator_vcm.h): eta = N pi r^2 (N light paths merged with, radius r) makes the weights count
  // merging at every vertex as a strategy (0: bdpt, no merging); connect = false leaves the connections out
  // of the weights and of connect() but s = 0 (ppm: merging only).
  double eta = 0;
  bool connect = true;
};

/// Connects the subpaths of sample `path` (the same index in both stores and both path states). Contributions
/// of camera-side strategies go to camera_paths.radiance[path] (s = 0) or to `shadows`; t = 1 to `splats`.
class BdptConnector {
 public:
  BdptConnector(const Scene& scene, const Camera& camera, const Sampler& sampler, const BdptConnectRules& rules)
      : scene_(scene), camera_(camera), sampler_(sampler), rules_(rules) {}

  void connect(uint32_t path, const BdptStore& light, const BdptStore& camera, PathState& camera_paths,
               ShadowQueue& shadows, CameraQueue& splats) {
    connect(path, light, path, camera, camera_paths, shadows, splats);
  }
  /// connect() with the light subpath `light_path` of `light` (VCM keeps one store of the iteration's subpaths).
  void connect(uint32_t path, const BdptStore& light, uint32_t light_path, const BdptStore& camera,
               PathState& camera_paths, ShadowQueue& shadows, CameraQueue& splats);

  /// VCM: the eta of the current iteration (its radius shrinks); 0: no merging.
  void set_eta(double eta) { rules_.eta = eta; }

  /// Sets the camera subpath of sample `path` for merge() calls; returns its vertex count.
  int begin_merges(uint32_t path, const BdptStore& camera);
  /// Merging (VCM) of camera vertex tc (>= 1) of the subpath set by begin_merges with light vertex `photon` of
  /// `photons` (a surface vertex, not the light's): camera throughput * BSDF * photon throughput, MIS-weighted
  /// over every strategy of the path (connections and merges at each vertex), before the kernel's 1 / (N pi r^2).
  Rgb merge(int tc, const BdptStore& camera, const BdptStore& photons, uint32_t photon);

 private:
  // Strategy (s, t) of the sample: its contribution, MIS-weighted, to the path, `shadows` or `splats`.
  void strategy(int s, int t, uint32_t path, const BdptStore& light, const BdptStore& camera,
                PathState& camera_paths, ShadowQueue& shadows, CameraQueue& splats);
  // The MIS weight of strategy (s, t) with the densities in lf_/lr_/ld_ and cf_/cr_/cd_ (already overridden
  // at the connection's vertices); light_delta: the light vertex is a point-like light.
  double mis_weight(int s, int t, bool light_delta) const;
  // Sum over the strategies that make the path of (their density / strategy (s, t)'s)^2, the connections
  // counted where enabled (rules_.connect, s = 0 always) and the merges where rules_.eta > 0.
  double mis_sum(int s, int t, bool light_delta) const;
  // The term of merging at light vertex s - 1 in mis_sum (0 where that cannot merge).
  double own_merge_term(int s) const;
  void load_densities(const BdptStore& light, const BdptStore& camera);

  const Scene& scene_;
  const Camera& camera_;
  const Sampler& sampler_;
  BdptConnectRules rules_;
  std::vector<uint32_t> lchain_, cchain_;
  // Densities of the current strategy (copied from the vertices, then overridden where it connects).
  std::vector<float> lf_, lr_, cf_, cr_;
  std::vector<uint8_t> ld_, cd_;
};

}  // namespace torte
