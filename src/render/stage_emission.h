// Stage: light found by the path's own rays, weighted by MIS against the light-sampling strategy that could
// have found it: escaped rays (infinite lights) and hits on emitting surfaces (area lights, emitting voxel faces
// and cell shapes). Runs after sort_hits (stage_hits.h), which reconstructs the surfaces and changes no path
// state emission reads.
#pragma once
#include <cstdint>

#include "light/light.h"
#include "render/path_state.h"

namespace torte {

// MIS weight of emission found by BSDF sampling on path i (light `light_index` of pdf `light_pdf` for the ray).
inline float emission_weight(const Scene& scene, const PathState& ps, const TransportRules& rules, uint32_t i,
                             int light_index, float light_pdf) {
  // Seen by the camera or through a delta lobe: no light sampling competes.
  if (ps.depth[i] == 0 || (ps.flags[i] & kPathSpecular)) return 1.0f;
  const float pmf = rules.sample_all_lights                          ? 1.0f
                    : rules.light_sampler == LightSamplerKind::Bvh ? scene.light_bvh.pmf(ps.prev_p[i], ps.prev_n[i], light_index)
                                                                   : scene.light_selection.pmf(light_index);
  return power_heuristic(1, ps.bsdf_pdf[i], 1, pmf * light_pdf);
}

/// Adds the radiance of the infinite lights seen along escaped ray (o, d) to path i.
inline void add_escaped_radiance(const Scene& scene, const TransportRules& rules, PathState& ps, uint32_t i, Vec3f o,
                                 Vec3f d) {
  for (const uint32_t l : scene.infinite_lights) {
    const Light& light = scene.lights[l];
    const Rgb le = escaped_radiance(light, d);
    if (le.is_black()) continue;
    const float w = emission_weight(scene, ps, rules, i, int(l), light_pdf(scene, light, o, d, nullptr, kInfinity));
    ps.radiance[i] += ps.beta[i] * le * w;
  }
}

/// Adds the emission of surface `s` (hit at distance t along (o, d)) to path i.
inline void add_surface_emission(const Scene& scene, const TransportRules& rules, PathState& ps, uint32_t i, Vec3f o,
                                 Vec3f d, const SurfaceHit& s, float t) {
  const SceneObject& object = scene.objects[s.object];
  if (object.area_light >= 0) {
    const Light& light = scene.lights[size_t(object.area_light)];
    const Rgb le = area_emission(scene, light, s, d);
    if (!le.is_black()) {
      const float w = emission_weight(scene, ps, rules, i, object.area_light, light_pdf(scene, light, o, d, &s, t));
      ps.radiance[i] += ps.beta[i] * le * w;
    }
  } else if (const SurfaceEmission* e = patch_emission_towards(scene, s, d)) {
    // An emitting voxel face or cell shape (a Patches light). The light BVH samples one part of it at a time:
    // the density is that of the hit patch's part, times the part's probability.
    const Light& light = scene.lights[size_t(e->light)];
    float w = 1;
    if (ps.depth[i] > 0 && !(ps.flags[i] & kPathSpecular) && !rules.sample_all_lights &&
        rules.light_sampler == LightSamplerKind::Bvh) {
      uint32_t part;
      const float pdf = patch_pdf_in_part(light, o, d, s, t, &part);
      w = power_heuristic(1, ps.bsdf_pdf[i], 1, scene.light_bvh.pmf(ps.prev_p[i], ps.prev_n[i], e->light, part) * pdf);
    } else {
      w = emission_weight(scene, ps, rules, i, e->light, light_pdf(scene, light, o, d, &s, t));
    }
    ps.radiance[i] += ps.beta[i] * e->radiance * w;
  }
}

/// Adds to each path of `rays` the light its ray found: infinite lights if it escaped, else the emission of the
/// surface it hit (hits.surface, as sort_hits reconstructed it).
inline void add_emission(const Scene& scene, const TransportRules& rules, const RayQueue& rays, const HitQueue& hits,
                         PathState& ps) {
  if (!rules.add_emission) return;
  for (size_t k = 0; k < rays.size(); ++k) {
    const uint32_t i = rays.path[k];
    const Hit& hit = hits.hit[k];
    if (hit.prim == kNoHit)
      add_escaped_radiance(scene, rules, ps, i, rays.origin(k), rays.dir(k));
    else
      add_surface_emission(scene, rules, ps, i, rays.origin(k), rays.dir(k), hits.surface[k], hit.t);
  }
}

}  // namespace torte
