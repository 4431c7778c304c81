// Integrator `bdpt`: bidirectional path tracing (Veach 1997, ch. 10; the formulation of pbrt's BDPT). Each
// camera sample request (pixel, sample) traces one camera subpath and one light subpath, then joins them in
// every way: s light vertices and t camera vertices for all s + t - 2 <= max_depth (s = 0: the camera
// subpath hits an emitter; s = 1: a light point sampled at a camera vertex, next-event estimation; t = 1: a
// light vertex connected to the lens and splatted to the film; the others join two surface vertices by a
// shadow ray), each weighted by the power heuristic over all strategies that make the same path.
//
//   parameter   type   default  meaning
//   spp         int    16       samples per pixel: each is a camera subpath, a light subpath and their connections
//   max_depth   int    64       largest number of scattering events on a path (0: emitters seen directly only)
//   rr_depth    int    3        Russian roulette on both subpaths from this many scattering events on
//   seed        int    0        the sampler's seed
//
// MIS weights are computed from ratios of densities, one vertex at a time (pbrt's remapping), in double
// precision: no product of densities is formed, so none overflows. The light subpaths start as light
// tracing's do (scene.light_selection by power, then sample_emission); the s = 1 strategy chooses its light
// the same way and its point by area (area lights), so the densities the weights use are the real ones.
// Specular (delta) lobes: a vertex left through one gets pdf 0 (remapped to 1) and is never an endpoint of
// a connection; point and spot lights are delta in position (no s = 0 strategy competes with them).
//
// The subpaths advance on the wavefront: trace_rays, sort_hits and a kernel per material type
// (shade_subpath_queue, render/bdpt_subpath.h) that keeps every vertex and its BSDF (in a pool per material
// type, evaluated through dispatch_shaded: no virtual call). The connections (render/bdpt_connect.h) of a
// wavefront are traced as two batches of shadow rays (radiance to the camera paths, splats to the tile's
// SplatBuffer, merged in tile order), so the image is bitwise identical for any thread count. Memory: a
// wavefront of kWavefrontSamples (1024) samples keeps at most (max_depth + 1) light and (max_depth + 2) camera
// vertices per sample (about 96 bytes each plus its BSDF), and the connection queues at most one shadow ray
// per strategy; the buffers keep the capacity of the largest wavefront seen and never grow past that bound.
//
// Supported: area lights on meshes and quadrics, point and spot lights; a perspective camera (pinhole or thin
// lens) placed rigidly. render_bdpt refuses the rest (distant lights, lights at infinity, emitting voxels;
// orthographic cameras) with an error naming the light or the camera.
#pragma once
#include <atomic>
#include <string>

#include "render/render.h"

namespace torte {

struct BdptSettings {
  int max_depth = 64;
  int rr_depth = 3;
  // Tests and debugging only: when only_s >= 0 the image holds the MIS-weighted strategy (only_s, only_t).
  int only_s = -1, only_t = -1;
  static BdptSettings from(const RenderSettings& s) { return {s.max_depth, s.rr_depth}; }
  // Camera subpaths continue to depth max_depth, where only emission is read (strategy s = 0); light subpaths
  // stop one vertex earlier (their last vertex only connects to the camera). add_emission is off: the
  // connection stage adds emission with its MIS weight.
  TransportRules rules() const { return {max_depth, rr_depth, false, false, false}; }
};

/// Why bdpt cannot render this scene with this camera ("" if it can).
std::string bdpt_problem(const Scene& scene, const Camera& camera);

/// Renders with bidirectional path tracing (settings already validated, camera made for their size).
/// Throws torte::Error naming the light or camera bdpt does not support.
RenderOutput render_bdpt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         ProgressSink* progress, const std::atomic<bool>* cancel);

/// render_bdpt with its own settings (tests select single strategies through BdptSettings::only_s/only_t).
RenderOutput render_bdpt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         const BdptSettings& bdpt, ProgressSink* progress = nullptr,
                         const std::atomic<bool>* cancel = nullptr);

}  // namespace torte
