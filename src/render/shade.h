// Shading kernels: one per material type, each run over a whole queue of hits of that type. A kernel samples
// a light (next-event estimation, weighted by MIS against BSDF sampling), queues the shadow ray, samples the
// BSDF for the path's next ray and applies Russian roulette. Templated on the material type, so the BSDF calls
// inline and the loop has no per-hit dispatch.
#pragma once
#include <span>

#include "core/sampler.h"
#include "material/lambert.h"
#include "render/path_state.h"
#include "render/render.h"

namespace torte {

// Sample dimensions of one path: 0 is the filter; each scattering event then uses kDimsPerBounce.
enum SampleDim : uint32_t { kDimFilter = 0, kDimFirstBounce = 1 };
enum BounceDim : uint32_t { kDimLightSelect = 0, kDimLightPoint = 1, kDimBsdf = 2, kDimRoulette = 3, kDimsPerBounce = 4 };
// Per-light dimensions when every light is sampled at every vertex.
constexpr uint32_t kDimAllLightsBase = 1u << 20;

struct ShadeContext {
  const Scene& scene;
  const RenderSettings& settings;
  const Sampler& sampler;
  PathState& paths;
  ShadowQueue& shadows;
};

template <MaterialType T>
struct MaterialTraits;

template <>
struct MaterialTraits<MaterialType::Lambert> {
  static LambertBsdf bsdf(const MaterialTables& tables, uint32_t index, const SurfaceHit&) {
    return {tables.lambert[index].albedo};
  }
};

namespace detail {

// Next-event estimation towards one light, chosen with probability `pmf`.
template <class Bsdf>
void sample_one_light(const ShadeContext& ctx, uint32_t path, const Bsdf& bsdf, const Frame& frame, Vec3f p,
                      Vec3f ng, Vec3f wo_local, const Light& light, float pmf, Vec2f u) {
  LightSample ls;
  if (!sample_light(ctx.scene, light, p, u, &ls)) return;
  if (dot(ls.wi, ng) <= 0) return;  // arrives from behind the (oriented) surface
  const Vec3f wi_local = frame.to_local(ls.wi);
  const Rgb f = bsdf.eval(wo_local, wi_local) * std::fabs(wi_local.z);
  if (f.is_black()) return;
  const float light_pdf = pmf * ls.pdf;
  const float weight = ls.delta ? 1.0f : power_heuristic(1, light_pdf, 1, bsdf.pdf(wo_local, wi_local));
  const Rgb contribution = ctx.paths.beta[path] * f * ls.radiance * (weight / light_pdf);
  if (contribution.is_black()) return;
  const Vec3f o = offset_origin(p, ng, ls.wi);
  float t_max = kInfinity;
  if (ls.distance != kInfinity) {
    // Stop just short of the light point (measured from the offset origin) so the light does not shadow itself.
    const Vec3f q = p + ls.wi * ls.distance;
    t_max = length(q - o) * (1 - 1e-4f);
  }
  ctx.shadows.push(o, ls.wi, t_max, contribution, path);
}

}  // namespace detail

// Shades the paths in `queue` (all hitting material type T). Paths that end get depth kPathEnded.
template <MaterialType T>
void shade_queue(const ShadeContext& ctx, std::span<const uint32_t> queue) {
  const Scene& scene = ctx.scene;
  PathState& ps = ctx.paths;
  for (const uint32_t i : queue) {
    const SurfaceHit& s = ps.surface[i];
    const MaterialRef mat = scene.objects[s.object].material;
    const auto bsdf = MaterialTraits<T>::bsdf(scene.materials, mat.index, s);
    const Vec3f wo = -ps.dir[i];
    // Shade on the side the ray arrived from: the materials so far reflect only.
    const bool back = dot(s.ng, wo) < 0;
    const Vec3f ng = back ? -s.ng : s.ng;
    const Vec3f ns = back ? -s.ns : s.ns;
    const Frame frame = Frame::from_z(ns);
    const Vec3f wo_local = frame.to_local(wo);
    const uint32_t px = ps.pixel[i], si = ps.sample[i];
    const uint32_t dim = kDimFirstBounce + uint32_t(ps.depth[i]) * kDimsPerBounce;

    // Next-event estimation.
    if (!scene.lights.empty()) {
      if (ctx.settings.sample_all_lights) {
        for (size_t l = 0; l < scene.lights.size(); ++l) {
          const Vec2f u = ctx.sampler.get_2d(px, si, kDimAllLightsBase + uint32_t(ps.depth[i]) * 4096 + uint32_t(l));
          detail::sample_one_light(ctx, i, bsdf, frame, s.p, ng, wo_local, scene.lights[l], 1.0f, u);
        }
      } else {
        float pmf;
        const int l = scene.light_selection.sample_discrete(ctx.sampler.get_1d(px, si, dim + kDimLightSelect), &pmf);
        if (pmf > 0)
          detail::sample_one_light(ctx, i, bsdf, frame, s.p, ng, wo_local, scene.lights[l], pmf,
                                   ctx.sampler.get_2d(px, si, dim + kDimLightPoint));
      }
    }

    // BSDF sampling for the path's next ray.
    typename decltype(bsdf)::Sample bs;
    if (!bsdf.sample(wo_local, ctx.sampler.get_2d(px, si, dim + kDimBsdf), &bs)) {
      ps.depth[i] = kPathEnded;
      continue;
    }
    const Vec3f wi = frame.to_world(bs.wi);
    if (dot(wi, ng) <= 0) {  // the shading normal sent the ray below the surface
      ps.depth[i] = kPathEnded;
      continue;
    }
    Rgb beta = ps.beta[i] * bs.weight;
    // Russian roulette: survival probability follows the throughput, compensated by 1/q (unbiased).
    if (ps.depth[i] + 1 >= ctx.settings.rr_depth) {
      const float q = std::min(0.95f, beta.max_component());
      if (!(ctx.sampler.get_1d(px, si, dim + kDimRoulette) < q)) {
        ps.depth[i] = kPathEnded;
        continue;
      }
      beta = beta / q;
    }
    ps.beta[i] = beta;
    ps.bsdf_pdf[i] = bs.pdf;
    ps.origin[i] = offset_origin(s.p, ng, wi);
    ps.dir[i] = wi;
    ps.depth[i] += 1;
  }
}

}  // namespace torte
