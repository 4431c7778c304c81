// Integrators `vcm` and `ppm`: vertex connection and merging (Georgiev, Krivanek, Davidovic and Slusallek 2012,
// "Light transport simulation with vertex connection and merging") and, from the same code, progressive photon
// mapping (merging only). Each sample index is one iteration: every pixel's light subpath of that sample is
// traced first (all of them, in parallel), their surface vertices (the photons) go into a hash grid, and then
// every camera subpath of the iteration is connected as bdpt connects it (render/integrator_bdpt.h: every (s,
// t), with its own light subpath, that of the same pixel and sample) and merged at each of its vertices with
// the photons within the iteration's radius of it.
//
//   parameter   type   default  meaning
//   spp         int    16       iterations (samples per pixel); each traces width * height light subpaths
//   max_depth   int    64       largest number of scattering events on a path (0: emitters seen directly only)
//   rr_depth    int    3        Russian roulette on both subpaths from this many scattering events on
//   seed        int    0        the sampler's seed
//   radius      float  0.01     the merge radius of the first iteration, relative to the scene's bounding radius
//   alpha       float  0.75     the radius schedule: iteration i (1, 2, ...) merges within r * i^((alpha - 1) / 2)
//                               (Knaus and Zwicker 2011; alpha in (0, 1]: 1 keeps the radius, smaller shrinks it
//                               faster, trading bias for noise)
//
// The radius default: 0.01 of the bounding radius is about 1/100 of a room's half width, so a 512x512 image's
// 262144 photon paths of an iteration put a few photons in each query; SmallVCM's 0.003 suits its scenes seen
// closer. Merging is a biased but consistent estimate: its bias is a blur of the lighting over the radius, which
// falls as the radius shrinks.
//
// MIS: one power-heuristic weight over every connection strategy and every merge of the path, in bdpt's
// density-ratio form (render/bdpt_connect.h) with merging at a vertex counted as the connection strategy ending
// at that light vertex times eta * (the camera subpath's density of the vertex), eta = N pi r^2 (N = width *
// height light paths of the iteration). `ppm` counts s = 0 (emitters the camera subpath hits) and the merges
// only, and traces no connection: camera subpaths are merged at every non-specular vertex, MIS-weighted.
//
// Deterministic at any thread count: light subpaths are traced per pixel chunk into their own store, the grid
// is sorted by (bucket, photon) and each camera vertex sums its photons in that fixed order. Memory: the
// iteration's light subpaths, at most (max_depth + 1) vertices (about 96 bytes plus its BSDF) per pixel, and
// 16 bytes per photon in the grid; kept at the capacity of the largest iteration, never growing past it.
// Supported lights and cameras: as bdpt.
#pragma once
#include <atomic>
#include <cmath>
#include <string>

#include "render/render.h"

namespace torte {

struct VcmSettings {
  int max_depth = 64;
  int rr_depth = 3;
  float radius = 0.01f;  // relative to the scene's bounding radius
  float alpha = 0.75f;
  bool connect = true;  // false: ppm
  bool merge = true;    // tests: false makes vcm bdpt (connections only, bdpt's weights)
  static VcmSettings from(const RenderSettings& s) {
    return {s.max_depth, s.rr_depth, s.merge_radius, s.merge_alpha, s.integrator != IntegratorKind::Ppm, true};
  }
  TransportRules rules() const { return {max_depth, rr_depth, false, false, false}; }
  /// The merge radius (world units) of iteration `i` (1, 2, ...) in a scene of bounding radius `scene_radius`.
  float radius_at(int i, float scene_radius) const {
    return radius * scene_radius * std::pow(float(i), (alpha - 1) / 2);
  }
};

/// Renders with vertex connection and merging or progressive photon mapping (settings.integrator Vcm or Ppm;
/// settings validated, camera made for their size). Throws torte::Error naming what bdpt does not support.
RenderOutput render_vcm(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        ProgressSink* progress, const std::atomic<bool>* cancel);

/// render_vcm with its own settings (tests switch merging off through VcmSettings::merge).
RenderOutput render_vcm(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        const VcmSettings& vcm, ProgressSink* progress = nullptr,
                        const std::atomic<bool>* cancel = nullptr);

}  // namespace torte
