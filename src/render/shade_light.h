// Shading kernel of light-path vertices, one per material type like shade_queue (render/shade.h), with the same
// phases and scratch: BSDFs built in TransportMode::Importance; instead of sampling the lights, every vertex
// with a non-specular BSDF is connected to the camera (Camera::sample_wi), the connections' BSDF values come
// from the same batch evaluation, and each becomes a shadow ray towards the lens carrying its splat; then the
// path moves on by BSDF sampling with the adjoint shading-normal factor (continue_path).
#pragma once
#include <cmath>
#include <span>
#include <vector>

#include "camera/camera.h"
#include "render/shade.h"
#include "render/stage_light.h"

namespace torte {

// Shades the light-path slots in `queue` (all of material type T), pushing their camera connections to
// `connections` and their next rays to ctx.next. `raster` is scratch (one entry per connection candidate).
// A connection at the vertex that ends the path's k-th segment adds paths of k scattering events.
template <MaterialType T>
void shade_light_queue(const ShadeContext& ctx, const Camera& camera, std::span<const uint32_t> queue,
                       ShadeScratch<typename MaterialTraits<T>::Bsdf>& sc, std::vector<Vec2f>& raster,
                       CameraQueue& connections) {
  using Traits = MaterialTraits<T>;
  const Scene& scene = ctx.scene;
  PathState& ps = ctx.paths;
  const size_t n = queue.size();
  sc.begin(n);
  raster.clear();

  // Phase 1: BSDFs and camera samples (a LightCandidate each: radiance holds We / pdf, distance the lens's).
  for (size_t k = 0; k < n; ++k) {
    const uint32_t slot = queue[k], i = ctx.rays.path[slot];
    const SurfaceHit& s = ctx.hits.surface[slot];
    sc.bsdf.push_back(Traits::bsdf(scene.materials, scene.textures, ctx.hits.material[slot].index,
                                   texture_context(s, ps.footprint[i]), TransportMode::Importance));
    sc.frame[k] = Frame::from_z(s.ns);
    const Vec3f wo = -ctx.rays.dir(slot);
    sc.wo_local[k] = sc.frame[k].to_local(wo);
    if (!sc.bsdf.back().has_non_specular()) continue;
    CameraWiSample cs;
    if (!camera.sample_wi(s.p, ctx.sampler.get_2d(ps.pixel[i], ps.sample[i], bounce_dim(ps.depth[i], kDimLightPoint)),
                          &cs))
      continue;
    const Vec3f wi_local = sc.frame[k].to_local(cs.wi);
    if (!consistent_sides(s.ng, wo, cs.wi, sc.wo_local[k], wi_local)) continue;
    sc.lights.push_back({uint32_t(k), cs.wi, wi_local, Rgb(cs.we / cs.pdf), cs.pdf, cs.distance, true});
    raster.push_back(cs.raster);
  }

  // Phase 2: BSDF values of all connections.
  detail::eval_candidates<T>(sc);

  // Phase 3: the splat each connection carries, f |wo.ns| |wi.ng| / |wo.ng| (the adjoint factor times the
  // shading cosine) times We / pdf, and its shadow ray.
  for (size_t k = 0; k < sc.lights.size(); ++k) {
    const LightCandidate& c = sc.lights[k];
    const uint32_t slot = queue[c.slot], i = ctx.rays.path[slot];
    const SurfaceHit& s = ctx.hits.surface[slot];
    const float cos_g_wo = std::fabs(dot(ctx.rays.dir(slot), s.ng));
    if (sc.f[k].is_black() || !(cos_g_wo > 0)) continue;
    const float factor = std::fabs(sc.wo_local[c.slot].z) * std::fabs(dot(c.wi, s.ng)) / cos_g_wo;
    const Rgb value = ps.beta[i] * sc.f[k] * c.radiance * (factor * ps.filter_weight[i]);
    if (value.is_black()) continue;
    const Vec3f o = offset_origin(s.p, s.ng, c.wi);
    connections.push(o, c.wi, length(s.p + c.wi * c.distance - o) * (1 - 1e-4f), value, i, raster[k]);
  }

  // Phase 4: BSDF sampling for the paths' next rays, with the adjoint shading-normal factor.
  detail::sample_next_rays<T>(ctx, queue, sc, TransportMode::Importance);
}

}  // namespace torte
