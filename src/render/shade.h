// Shading kernels: one per material type, each run over the whole queue of hits of that type, in phases so
// that every phase is a tight loop over arrays:
//   1. build the BSDF of every hit (texture lookups) and sample the lights (next-event estimation);
//   2. evaluate f and pdf for all light samples at once (MaterialTraits<T>::eval_batch when the type has a
//      vectorised kernel, else a scalar loop);
//   3. weight the light samples by MIS and queue the shadow rays;
//   4. sample the BSDF for each path's next ray and apply Russian roulette; survivors go to the next ray queue.
// Between 3 and 4 an integrator may look at the queue (OnShaded, e.g. IGI gathers VPL light at the hits).
// Templated on the material type, so BSDF calls inline and no hit pays a per-hit dispatch.
#pragma once
#include <algorithm>
#include <cmath>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/sampler.h"
#include "material/material_traits.h"
#include "render/shade_eval_batch.h"
#include "render/material_resolve.h"
#include "render/path_state.h"

namespace torte {

// Sample dimensions of one path: 0 is the filter; each scattering event then uses kDimsPerBounce. A 1D use
// takes a dimension of its own (get_1d(d) equals get_2d(d).x).
enum SampleDim : uint32_t { kDimFilter = 0, kDimFirstBounce = 1 };
enum BounceDim : uint32_t {
  kDimLightSelect = 0,
  kDimLightPoint = 1,
  kDimBsdf = 2,
  kDimBsdfLobe = 3,
  kDimRoulette = 4,
  kDimMaterialMix = 5,
  kDimsPerBounce = 6
};
// Per-light dimensions when every light is sampled at every vertex.
constexpr uint32_t kDimAllLightsBase = 1u << 20;

inline uint32_t bounce_dim(uint16_t depth, BounceDim d) {
  return kDimFirstBounce + uint32_t(depth) * kDimsPerBounce + d;
}

/// What a shading kernel reads and writes. Queue entries are slots of `rays` / `hits` (the wavefront being
/// shaded); paths that go on push their next ray to `next`, in the order they are shaded.
struct ShadeContext {
  const Scene& scene;
  const TransportRules& rules;
  const Sampler& sampler;
  PathState& paths;
  const RayQueue& rays;
  const HitQueue& hits;
  RayQueue& next;
  ShadowQueue& shadows;
};

// A light sample waiting for its BSDF evaluation (phase 2) and MIS weighting (phase 3).
struct LightCandidate {
  uint32_t slot;   // index of the hit within the queue
  Vec3f wi;        // world direction to the light
  Vec3f wi_local;  // in the hit's shading frame
  Rgb radiance;    // arriving radiance if unoccluded
  float light_pdf; // selection pmf times the light's solid-angle pdf
  float distance;  // to the light point (kInfinity for infinite lights)
  bool delta;      // point-like light: no MIS
};

// The sampler's numbers the scattering events of a queue use, by queue entry. A kernel draws them for the whole
// queue before it shades (draw_light_numbers, draw_scatter_numbers), in vector lanes (Sampler::get_batch): one
// at a time inside the shading loop they were its largest cost after tracing.
struct ShadeNumbers {
  std::vector<float> light_select, light_x, light_y, bsdf_x, bsdf_y, lobe, roulette;
  std::vector<uint32_t> pixel, sample, dim, scratch;  // the requests, and the batch's scratch
  // The light BVH's choices (LightBvh::sample_batch) for the entries with a non-specular BSDF, in queue order.
  std::vector<uint32_t> chosen_part;
  std::vector<Vec3f> chooser_p, chooser_n;
  std::vector<float> chooser_u, chosen_pmf;
  std::vector<int> chosen;
  void resize(size_t n) {
    for (auto* v : {&light_select, &light_x, &light_y, &bsdf_x, &bsdf_y, &lobe, &roulette, &chooser_u, &chosen_pmf})
      v->resize(n);
    for (auto* v : {&pixel, &sample, &dim, &chosen_part}) v->resize(n);
    chooser_p.resize(n);
    chooser_n.resize(n);
    chosen.resize(n);
    scratch.resize(3 * n);
  }
};

// Per-type scratch arrays, reused between wavefronts.
template <class Bsdf>
struct ShadeScratch {
  std::vector<Bsdf> bsdf;
  std::vector<Frame> frame;
  std::vector<Vec3f> wo_local;
  std::vector<LightCandidate> lights;
  std::vector<Rgb> f;
  std::vector<float> pdf;
  ShadeNumbers u;  // the queue's sampler numbers, drawn before they are used
  /// Ready for a queue of n hits: frames, local directions and numbers sized, BSDFs and light candidates emptied.
  void begin(size_t n) {
    bsdf.clear();
    frame.resize(n);
    wo_local.resize(n);
    u.resize(n);
    lights.clear();
  }
};

// True when geometry and shading normals agree on whether wo -> wi is a reflection or a transmission. When they
// disagree (interpolated normals far from the facet), the light would leak through the surface: drop it.
inline bool consistent_sides(Vec3f ng, Vec3f wo, Vec3f wi, Vec3f wo_local, Vec3f wi_local) {
  return (dot(wo, ng) * dot(wi, ng) > 0) == (wo_local.z * wi_local.z > 0);
}

// Queues the shadow ray from hit `s` towards a light point at `distance` along wi (kInfinity for lights at
// infinity), carrying `contribution` to path i if unoccluded.
inline void push_shadow_ray(ShadowQueue& shadows, const SurfaceHit& s, Vec3f wi, float distance, Rgb contribution,
                            uint32_t path) {
  const Vec3f o = offset_origin(s.p, s.ng, wi);
  if (distance == kInfinity) {
    shadows.push(o, wi, kInfinity, contribution, path);
    return;
  }
  // Aimed at the light point (ray_towards): along wi the offset moved the ray sideways, and a sphere light's own
  // surface stopped up to four fifths of the rays meant for it.
  const Ray r = ray_towards(o, s.p + wi * distance, wi, 1e-4f);
  shadows.push(r.o, r.d, r.t_max, contribution, path);
}

// Continues the path of queue slot `slot` with the BSDF sample `bs` (drawn in `frame`, wo_local being the
// outgoing direction): checks the sides, updates throughput and flags, applies Russian roulette and pushes the
// next ray to ctx.next. A path that stops here is simply not pushed. Light paths (TransportMode::Importance)
// also take the adjoint shading-normal factor |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|) (Veach 1997, 5.3).
// `dim_base` offsets the roulette's sampler dimension (BDPT's light subpaths, as in sort_hits).
// `u_roulette` is the path's roulette number (read only from rules.rr_depth events on).
inline void continue_path_with(const ShadeContext& ctx, uint32_t slot, const Frame& frame, Vec3f wo_local,
                               const BsdfSample& bs, TransportMode mode, float u_roulette) {
  PathState& ps = ctx.paths;
  const uint32_t i = ctx.rays.path[slot];
  const SurfaceHit& s = ctx.hits.surface[slot];
  const uint16_t depth = ps.depth[i];
  const Vec3f wi = frame.to_world(bs.wi);
  const Vec3f wo = -ctx.rays.dir(slot);
  if (!consistent_sides(s.ng, wo, wi, wo_local, bs.wi)) return;
  Rgb beta = ps.beta[i] * bs.weight();
  if (mode == TransportMode::Importance) {
    const float adjoint = std::fabs(wo_local.z) * std::fabs(dot(wi, s.ng)) / (std::fabs(dot(wo, s.ng)) * std::fabs(bs.wi.z));
    if (!(adjoint > 0) || !std::isfinite(adjoint)) return;
    beta = beta * adjoint;
  }
  if (bs.is_transmission()) ps.eta_scale[i] *= bs.eta * bs.eta;
  // Russian roulette on the throughput without the eta^2 radiance scaling of refraction (pbrt-v4), so paths
  // inside glass are not cut for carrying "too much" radiance; compensated by 1/q (unbiased).
  if (depth + 1 >= ctx.rules.rr_depth) {
    const float q = std::min(0.95f, (beta * ps.eta_scale[i]).max_component());
    if (!(u_roulette < q)) return;
    beta = beta / q;
  }
  ps.beta[i] = beta;
  ps.bsdf_pdf[i] = bs.pdf;
  ps.prev_p[i] = s.p;
  ps.prev_n[i] = s.ng;
  ps.flags[i] = bs.is_specular() ? kPathSpecular : kPathScattered;
  ps.depth[i] = uint16_t(depth + 1);
  ctx.next.push(offset_origin(s.p, s.ng, wi), wi, kInfinity, i);
}

// continue_path_with drawing the roulette number of the path's event itself; `dim_base` offsets its sampler
// dimension (BDPT's light subpaths, as in sort_hits).
inline void continue_path(const ShadeContext& ctx, uint32_t slot, const Frame& frame, Vec3f wo_local,
                          const BsdfSample& bs, TransportMode mode = TransportMode::Radiance, uint32_t dim_base = 0) {
  const PathState& ps = ctx.paths;
  const uint32_t i = ctx.rays.path[slot];
  const uint16_t depth = ps.depth[i];
  const float u = depth + 1 >= ctx.rules.rr_depth
                      ? ctx.sampler.get_1d(ps.pixel[i], ps.sample[i], dim_base + bounce_dim(depth, kDimRoulette))
                      : 0.0f;
  continue_path_with(ctx, slot, frame, wo_local, bs, mode, u);
}

/// The OnShaded hook of integrators that need none.
struct NoShadeHook {
  template <class Scratch>
  void operator()(const Scratch&, std::span<const uint32_t>) const {}
};

namespace detail {

// Phase 2: f and pdf for every light candidate.
template <MaterialType T, class Bsdf>
void eval_candidates(ShadeScratch<Bsdf>& sc) {
  const size_t n = sc.lights.size();
  sc.f.resize(n);
  sc.pdf.resize(n);
  if constexpr (MaterialTraits<T>::kBatchEval) {
    eval_batch_simd(sc);
  } else {
    for (size_t k = 0; k < n; ++k) {
      const LightCandidate& c = sc.lights[k];
      const Bsdf& b = sc.bsdf[c.slot];
      sc.f[k] = b.eval(sc.wo_local[c.slot], c.wi_local);
      sc.pdf[k] = b.pdf(sc.wo_local[c.slot], c.wi_local);
    }
  }
}

// The pixel and sample index of each queue entry's path into u.pixel, u.sample (the requests' common part).
inline void gather_requests(const ShadeContext& ctx, std::span<const uint32_t> queue, ShadeNumbers& u) {
  const PathState& ps = ctx.paths;
  for (size_t k = 0; k < queue.size(); ++k) {
    const uint32_t i = ctx.rays.path[queue[k]];
    u.pixel[k] = ps.pixel[i];
    u.sample[k] = ps.sample[i];
  }
}

// Draws dimension `d` of each queue entry's current event into x (and y): bounce_dim(depth, d) of its path.
inline void draw_bounce_dim(const ShadeContext& ctx, std::span<const uint32_t> queue, ShadeNumbers& u, BounceDim d,
                            float* x, float* y) {
  for (size_t k = 0; k < queue.size(); ++k) u.dim[k] = bounce_dim(ctx.paths.depth[ctx.rays.path[queue[k]]], d);
  ctx.sampler.get_batch(queue.size(), u.pixel.data(), u.sample.data(), u.dim.data(), x, y, u.scratch.data());
}

// Draws the numbers of BSDF sampling and Russian roulette (bsdf_x/y, lobe, roulette) for every queue entry. The
// roulette number is drawn for all and read only from rules.rr_depth events on.
template <MaterialType T>
void draw_scatter_numbers(const ShadeContext& ctx, std::span<const uint32_t> queue, ShadeNumbers& u) {
  gather_requests(ctx, queue, u);
  draw_bounce_dim(ctx, queue, u, kDimBsdf, u.bsdf_x.data(), u.bsdf_y.data());
  // Single-lobe models ignore the lobe sample: do not pay for a sampler dimension they do not read.
  if constexpr (MaterialTraits<T>::kSingleLobe)
    std::fill_n(u.lobe.begin(), queue.size(), 0.5f);
  else
    draw_bounce_dim(ctx, queue, u, kDimBsdfLobe, u.lobe.data(), nullptr);
  draw_bounce_dim(ctx, queue, u, kDimRoulette, u.roulette.data(), nullptr);
}

// Draws the numbers of light selection and the light point (light_select, light_x/y) for every queue entry.
inline void draw_light_numbers(const ShadeContext& ctx, std::span<const uint32_t> queue, ShadeNumbers& u) {
  gather_requests(ctx, queue, u);
  draw_bounce_dim(ctx, queue, u, kDimLightSelect, u.light_select.data(), nullptr);
  draw_bounce_dim(ctx, queue, u, kDimLightPoint, u.light_x.data(), u.light_y.data());
}

// Phase 4 of a shading kernel: samples each slot's BSDF (built in sc by phase 1) for its path's next ray and
// continues the path (continue_path, in transport `mode`); a path whose sample fails ends.
template <MaterialType T, class Bsdf>
void sample_next_rays(const ShadeContext& ctx, std::span<const uint32_t> queue, ShadeScratch<Bsdf>& sc,
                      TransportMode mode) {
  ShadeNumbers& u = sc.u;
  draw_scatter_numbers<T>(ctx, queue, u);
  for (size_t k = 0; k < queue.size(); ++k) {
    BsdfSample bs;
    if (!sc.bsdf[k].sample(sc.wo_local[k], u.lobe[k], Vec2f(u.bsdf_x[k], u.bsdf_y[k]), &bs) || !(bs.pdf > 0))
      continue;  // the path ends
    continue_path_with(ctx, queue[k], sc.frame[k], sc.wo_local[k], bs, mode, u.roulette[k]);
  }
}

inline void add_candidate(const EmitterView& emitters, std::vector<LightCandidate>& out, uint32_t slot,
                          const SurfaceHit& s, const Frame& frame, Vec3f wo, Vec3f wo_local, const Light& light,
                          float pmf, Vec2f u, uint32_t part = kWholeLight) {
  LightSample ls;
  if (!sample_light(emitters, light, s.p, u, &ls, part)) return;
  const Vec3f wi_local = frame.to_local(ls.wi);
  if (!consistent_sides(s.ng, wo, ls.wi, wo_local, wi_local)) return;
  out.push_back({slot, ls.wi, wi_local, ls.radiance, pmf * ls.pdf, ls.distance, ls.delta});
}

}  // namespace detail

// Shades the queue slots in `queue` (all resolved to material type T); on_shaded(sc, queue) runs after the light
// samples are queued and before the paths move on (sc then holds every slot's BSDF, frame and local wo).
template <MaterialType T, class OnShaded = NoShadeHook>
void shade_queue(const ShadeContext& ctx, std::span<const uint32_t> queue,
                 ShadeScratch<typename MaterialTraits<T>::Bsdf>& sc, OnShaded&& on_shaded = {}) {
  using Traits = MaterialTraits<T>;
  const Scene& scene = ctx.scene;
  PathState& ps = ctx.paths;
  const size_t n = queue.size();
  sc.begin(n);

  // Phase 1: BSDFs, then light samples (two loops: shorter bodies let the core overlap more hits' latency).
  for (size_t k = 0; k < n; ++k) {
    const uint32_t slot = queue[k], i = ctx.rays.path[slot];
    const SurfaceHit& s = ctx.hits.surface[slot];
    sc.bsdf.push_back(Traits::bsdf(scene.materials, scene.textures, ctx.hits.material[slot].index,
                                   texture_context(s, ps.footprint[i]), TransportMode::Radiance));
    sc.frame[k] = Frame::from_z(s.ns);
    sc.wo_local[k] = sc.frame[k].to_local(-ctx.rays.dir(slot));
  }
  if (!scene.lights.empty() && !ctx.rules.sample_all_lights) detail::draw_light_numbers(ctx, queue, sc.u);
  // The light BVH chooses for every entry with a non-specular BSDF at once, in vector lanes.
  const bool bvh = !scene.lights.empty() && !ctx.rules.sample_all_lights &&
                   ctx.rules.light_sampler == LightSamplerKind::Bvh;
  size_t choosers = 0;
  for (size_t k = 0; k < n && bvh; ++k) {
    if (!sc.bsdf[k].has_non_specular()) continue;
    const SurfaceHit& s = ctx.hits.surface[queue[k]];
    sc.u.chooser_p[choosers] = s.p;
    sc.u.chooser_n[choosers] = s.ng;
    sc.u.chooser_u[choosers++] = sc.u.light_select[k];
  }
  if (choosers > 0)
    scene.light_bvh.sample_batch(choosers, sc.u.chooser_p.data(), sc.u.chooser_n.data(), sc.u.chooser_u.data(),
                                 sc.u.chosen.data(), sc.u.chosen_pmf.data(), sc.u.chosen_part.data());
  const EmitterView emitters = scene.emitters();  // once, not per light sample
  for (size_t k = 0, next_choice = 0; k < n && !scene.lights.empty(); ++k) {
    if (!sc.bsdf[k].has_non_specular()) continue;
    const uint32_t slot = queue[k], i = ctx.rays.path[slot];
    const SurfaceHit& s = ctx.hits.surface[slot];
    const Vec3f wo = -ctx.rays.dir(slot);
    if (ctx.rules.sample_all_lights) {
      const uint32_t px = ps.pixel[i], si = ps.sample[i];
      for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Vec2f u = ctx.sampler.get_2d(px, si, kDimAllLightsBase + uint32_t(ps.depth[i]) * 4096 + uint32_t(l));
        detail::add_candidate(emitters, sc.lights, uint32_t(k), s, sc.frame[k], wo, sc.wo_local[k], scene.lights[l], 1,
                              u);
      }
    } else {
      float pmf;
      uint32_t part = kWholeLight;  // the BVH picks a part of a Patches light
      int l;
      if (bvh) {
        const size_t c = next_choice++;
        l = sc.u.chosen[c];
        pmf = sc.u.chosen_pmf[c];
        part = sc.u.chosen_part[c];
      } else {
        l = scene.light_selection.sample_discrete(sc.u.light_select[k], &pmf);
      }
      if (l >= 0 && pmf > 0)
        detail::add_candidate(emitters, sc.lights, uint32_t(k), s, sc.frame[k], wo, sc.wo_local[k], scene.lights[l], pmf,
                              Vec2f(sc.u.light_x[k], sc.u.light_y[k]), part);
    }
  }

  // Phase 2: BSDF values for all light samples.
  detail::eval_candidates<T>(sc);

  // Phase 3: MIS weights and shadow rays.
  for (size_t k = 0; k < sc.lights.size(); ++k) {
    const LightCandidate& c = sc.lights[k];
    const Rgb f = sc.f[k] * std::fabs(c.wi_local.z);
    if (f.is_black() || !(c.light_pdf > 0)) continue;
    const uint32_t slot = queue[c.slot], i = ctx.rays.path[slot];
    const float weight = c.delta ? 1.0f : power_heuristic(1, c.light_pdf, 1, sc.pdf[k]);
    const Rgb contribution = ps.beta[i] * f * c.radiance * (weight / c.light_pdf);
    if (contribution.is_black()) continue;
    push_shadow_ray(ctx.shadows, ctx.hits.surface[slot], c.wi, c.distance, contribution, i);
  }

  on_shaded(std::as_const(sc), queue);

  // Phase 4: BSDF sampling for the paths' next rays.
  detail::sample_next_rays<T>(ctx, queue, sc, TransportMode::Radiance);
}

}  // namespace torte
