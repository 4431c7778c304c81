// Integrator `lt`: light tracing (particle tracing). Paths start at the lights and every vertex with a
// non-specular BSDF is connected to the camera; the connections that arrive splat to the film.
//
//   parameter   type   default  meaning
//   spp         int    16       light paths per pixel: a pass of the image traces width * height * spp of them
//   max_depth   int    64       largest number of scattering events on a path (0: emitters seen directly only)
//   rr_depth    int    3        Russian roulette on light paths from this many scattering events on
//   seed        int    0        the sampler's seed (light paths and camera rays)
//
// Each camera sample request (pixel, sample) of the tile loop stands for one light path (its numbers come from
// the sampler under that pixel and sample, so the render is deterministic) plus one camera ray: light tracing
// with a pinhole can never reach the camera from a light's own surface point, so the emitters the camera sees
// directly (area lights, emitting voxel faces, infinite lights) come from a cheap camera pass of max_depth 0
// with the pixel filter, and the light paths' connections start at their first surface hit: nothing counts
// twice. Splats land in the pixel their raster position falls in (a box filter: `filter` applies to the camera
// pass only) and the image adds splat sums * width * height / (light paths traced), the pixel's mean radiance
// (camera/camera.h, importance normalisation).
//
// Light paths advance through the shared stages: trace_rays, sort_hits (without emission), and per material
// type shade_light_queue (render/shade_light.h: BSDFs in TransportMode::Importance, camera connections as a
// batch of shadow rays, BSDF sampling with the adjoint shading-normal factor). Each tile's splats go to its own
// SplatBuffer, merged into the film in tile order (render/tile_loop.h), so the image is bitwise identical for any
// thread count. Camera: perspective or orthographic, pinhole or thin lens, placed rigidly (Camera::connect_problem);
// render() refuses other placements.
//
// Light tracing finds caustics (L S+ D E) that path tracing samples badly, but cannot see paths through
// specular surfaces in front of the camera (L ... D S+ E, e.g. a mirror's reflection): like pbrt-v4's
// LightPathIntegrator, those are missing. Glossy surfaces seen by the camera are reached only through
// connections whose BSDF value is rarely large: the estimate is heavy-tailed there and converges slowly.
#pragma once
#include <atomic>

#include "render/render.h"

namespace torte {

struct LtSettings {
  int max_depth = 64;
  int rr_depth = 3;
  static LtSettings from(const RenderSettings& s) { return {s.max_depth, s.rr_depth}; }
  TransportRules light_rules() const { return {max_depth, rr_depth, false, false, false}; }
  TransportRules camera_rules() const { return {0, rr_depth, false, false, true}; }
};

/// Renders with light tracing (settings already validated, camera made for their size and connectable).
RenderOutput render_lt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                       ProgressSink* progress, const std::atomic<bool>* cancel);

}  // namespace torte
