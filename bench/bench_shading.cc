// Shading benchmarks on recorded hits (no ray tracing in the timed loops):
//   shading/wavefront      the renderer's path: hits counting-sorted by material type, shade_queue<T> per type
//                          (phased kernels, SIMD phase-2 evaluation where MaterialTraits<T>::kBatchEval)
//   shading/per_hit        the previous per-hit path: the same hits in arrival order, the BSDF of each built behind
//                          a virtual interface (tests/reference_path_tracer.h) and shaded alone
//   eval/<type>/scalar     phase 2 only: the scalar loop of shade.h over a queue's light candidates
//   eval/<type>/batch      phase 2 only: eval_batch_simd (gather to SoA + SIMD kernel + write back), which
//                          shade_queue uses for Oren-Nayar and Conductor (not Lambert: no gain)
//   eval/<type>/kernel     the SIMD kernel alone on pre-gathered SoA arrays (the gather's share is the difference)
// Hits: a 128x128 image at 2 spp of tests/material_room.h (walls, Oren-Nayar, mirror, rough gold, plastic, glass),
// camera hits and one bounce, shaded in wavefronts of 4096 hits (a 16x16 tile at 16 spp), as the renderer does.
// Msamples = hits shaded (shading/*) or light candidates evaluated (eval/*) per second of the thread's CPU time.
// The shading cases check each other: the same paths end, and the shadow-ray contributions agree.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "material_room.h"
#include "reference_path_tracer.h"
#include "render/shade.h"
#include "render/shade_eval_batch.h"
#include "shade_eval.h"

using namespace torte;

namespace {

constexpr size_t kWavefront = 4096;

struct Recording {
  std::shared_ptr<Scene> scene;
  RenderSettings settings;
  TransportRules rules;
  Sampler sampler{7};
  PathState recorded;  // one entry per hit, ready to shade: path i is queue slot i of rays and hits
  RayQueue rays;
  HitQueue hits;
  std::array<size_t, kShadedMaterialTypeCount> per_type{};
};

// Camera hits of every pixel, then the hits of one BSDF-sampled bounce from each (the per-hit reference BSDFs do
// the sampling; same sample dimensions as the renderer).
Recording* record() {
  static Recording* rec = [] {
    auto* r = new Recording;
    r->scene = test::material_room();
    r->settings.width = r->settings.height = 128;
    r->settings.spp = 2;
    const Scene& scene = *r->scene;
    const Camera camera(test::material_room_camera(), r->settings.width, r->settings.height);
    PathState& ps = r->recorded;
    reference::PerHitBsdf holder;
    auto push = [&](uint32_t px, uint32_t si, const Ray& ray_in, uint16_t depth, Rgb beta, float pdf, uint8_t flags,
                    SurfaceHit* out_s, MaterialRef* out_m) {
      Ray ray = ray_in;
      Hit hit;
      if (!scene.intersect(ray, &hit)) return false;
      SurfaceHit s = scene.surface(Ray{ray_in.o, ray_in.d, hit.t}, hit);
      const float footprint = camera.footprint_at_origin() + camera.spread_angle() * hit.t;
      const MaterialRef m = resolve_material(
          scene, scene.material_of(s), s, footprint,
          [&] { return r->sampler.get_1d(px, si, bounce_dim(depth, kDimMaterialMix)); }, px);
      const size_t i = ps.size();
      ps.resize(i + 1);
      ps.pixel[i] = px;
      ps.sample[i] = si;
      ps.filter_weight[i] = 1;
      r->rays.push(ray_in.o, ray_in.d, kInfinity, uint32_t(i));
      ps.beta[i] = beta;
      ps.radiance[i] = Rgb(0);
      ps.bsdf_pdf[i] = pdf;
      ps.depth[i] = depth;
      ps.flags[i] = flags;
      ps.eta_scale[i] = 1;
      ps.footprint[i] = footprint;
      r->hits.resize(i + 1);
      r->hits.material[i] = m;
      r->hits.hit[i] = hit;
      r->hits.surface[i] = s;
      ++r->per_type[size_t(m.type)];
      *out_s = s;
      *out_m = m;
      return true;
    };
    // Camera hits first (pixel order), then the bounce hits, like successive wavefronts.
    struct Pending {
      uint32_t px, si;
      Ray ray;
      Rgb beta;
      float pdf;
      uint8_t flags;
    };
    std::vector<Pending> bounces;
    for (int y = 0; y < r->settings.height; ++y)
      for (int x = 0; x < r->settings.width; ++x)
        for (uint32_t si = 0; si < uint32_t(r->settings.spp); ++si) {
          const uint32_t px = uint32_t(y * r->settings.width + x);
          const Vec2f u = r->sampler.get_2d(px, si, kDimFilter);
          const Ray ray = camera.generate_ray({float(x) + u.x, float(y) + u.y});
          SurfaceHit s;
          MaterialRef m;
          if (!push(px, si, ray, 0, Rgb(1), 0, 0, &s, &m)) continue;
          const Frame frame = Frame::from_z(s.ns);
          const reference::BsdfInterface& b = holder.build(scene, m, texture_context(s, 0));
          BsdfSample bs;
          if (!b.sample(frame.to_local(-ray.d), r->sampler.get_1d(px, si, bounce_dim(0, kDimBsdfLobe)),
                        r->sampler.get_2d(px, si, bounce_dim(0, kDimBsdf)), &bs) ||
              !(bs.pdf > 0))
            continue;
          const Vec3f wi = frame.to_world(bs.wi);
          bounces.push_back({px, si, Ray{offset_origin(s.p, s.ng, wi), wi, kInfinity}, bs.weight(), bs.pdf,
                             uint8_t(bs.is_specular() ? kPathSpecular : kPathScattered)});
        }
    for (const Pending& p : bounces) {
      SurfaceHit s;
      MaterialRef m;
      push(p.px, p.si, p.ray, 1, p.beta, p.pdf, p.flags, &s, &m);
    }
    return r;
  }();
  return rec;
}

// The mutable part of the path state, restored before every pass (both variants pay the same copy).
void restore(const PathState& from, PathState& to) {
  to.beta = from.beta;
  to.bsdf_pdf = from.bsdf_pdf;
  to.flags = from.flags;
  to.depth = from.depth;
  to.eta_scale = from.eta_scale;
}

// --------------------------------------------------------------------------------------- the wavefront kernels
template <size_t... T>
auto make_scratch(std::index_sequence<T...>) -> std::tuple<ShadeScratch<typename MaterialTraits<MaterialType(T)>::Bsdf>...>;
using Scratch = decltype(make_scratch(std::make_index_sequence<kShadedMaterialTypeCount>{}));

struct WavefrontShader {
  Scratch scratch;
  std::vector<uint32_t> queue;
  void shade(const ShadeContext& ctx, size_t begin, size_t end) {
    // Counting sort by material type (done in add_emission_and_queue in the renderer).
    uint32_t counts[kMaterialTypeCount] = {}, first[kMaterialTypeCount + 1] = {};
    for (size_t i = begin; i < end; ++i) ++counts[int(ctx.hits.material[i].type)];
    for (int t = 0; t < kMaterialTypeCount; ++t) first[t + 1] = first[t] + counts[t];
    uint32_t cursor[kMaterialTypeCount];
    std::copy(first, first + kMaterialTypeCount, cursor);
    queue.resize(end - begin);
    for (size_t i = begin; i < end; ++i) queue[cursor[int(ctx.hits.material[i].type)]++] = uint32_t(i);
    [&]<size_t... T>(std::index_sequence<T...>) {
      (shade_queue<MaterialType(T)>(ctx, std::span<const uint32_t>(queue.data() + first[T], counts[T]),
                                    std::get<T>(scratch)),
       ...);
    }(std::make_index_sequence<kShadedMaterialTypeCount>{});
  }
};

// ------------------------------------------------------------------------------- the per-hit virtual dispatch
// shade_queue's four phases for one hit, with the BSDF behind reference::BsdfInterface.
void shade_per_hit(const ShadeContext& ctx, uint32_t i, reference::PerHitBsdf& holder) {
  const Scene& scene = ctx.scene;
  PathState& ps = ctx.paths;
  const SurfaceHit& s = ctx.hits.surface[i];
  const reference::BsdfInterface& b = holder.build(scene, ctx.hits.material[i], texture_context(s, ps.footprint[i]));
  const Frame frame = Frame::from_z(s.ns);
  const Vec3f wo = -ctx.rays.dir(i), wo_local = frame.to_local(wo);
  const uint32_t px = ps.pixel[i], si = ps.sample[i];
  const uint16_t depth = ps.depth[i];
  if (!scene.lights.empty() && b.has_non_specular()) {
    float pmf;
    const int l = scene.light_selection.sample_discrete(ctx.sampler.get_1d(px, si, bounce_dim(depth, kDimLightSelect)),
                                                        &pmf);
    LightSample ls;
    if (pmf > 0 && sample_light(scene, scene.lights[size_t(l)], s.p,
                                ctx.sampler.get_2d(px, si, bounce_dim(depth, kDimLightPoint)), &ls)) {
      const Vec3f wi_local = frame.to_local(ls.wi);
      const float light_pdf = pmf * ls.pdf;
      if (consistent_sides(s.ng, wo, ls.wi, wo_local, wi_local)) {
        const Rgb f = b.eval(wo_local, wi_local) * std::fabs(wi_local.z);
        if (!f.is_black() && light_pdf > 0) {
          const float w = ls.delta ? 1.0f : power_heuristic(1, light_pdf, 1, b.pdf(wo_local, wi_local));
          const Rgb contribution = ps.beta[i] * f * ls.radiance * (w / light_pdf);
          if (!contribution.is_black()) push_shadow_ray(ctx.shadows, s, ls.wi, ls.distance, contribution, i);
        }
      }
    }
  }
  BsdfSample bs;
  if (!b.sample(wo_local, ctx.sampler.get_1d(px, si, bounce_dim(depth, kDimBsdfLobe)),
                ctx.sampler.get_2d(px, si, bounce_dim(depth, kDimBsdf)), &bs) ||
      !(bs.pdf > 0))
    return;  // the path ends (its depth stays)
  continue_path(ctx, i, frame, wo_local, bs);
}

enum class Variant { Wavefront, PerHit };

// Runs one pass of a variant over all recorded hits (in wavefronts); returns the total shadow contribution.
struct Pass {
  PathState ps;
  RayQueue next;
  ShadowQueue shadows;
  WavefrontShader wavefront;
  reference::PerHitBsdf holder;
  double contribution = 0;
  size_t shadow_rays = 0;
  void run(const Recording& r, Variant v) {
    restore(r.recorded, ps);
    contribution = 0;
    shadow_rays = 0;
    const size_t n = ps.size();
    for (size_t begin = 0; begin < n; begin += kWavefront) {
      const size_t end = std::min(n, begin + kWavefront);
      shadows.clear();
      next.clear();
      const ShadeContext ctx{*r.scene, r.rules, r.sampler, ps, r.rays, r.hits, next, shadows};
      if (v == Variant::Wavefront) wavefront.shade(ctx, begin, end);
      else
        for (size_t i = begin; i < end; ++i) shade_per_hit(ctx, uint32_t(i), holder);
      shadow_rays += shadows.size();
      for (size_t k = 0; k < shadows.size(); ++k) contribution += shadows.contribution[k].g;
    }
  }
};

void BM_Shading(benchmark::State& state, Variant v) {
  const Recording& r = *record();
  Pass pass;
  pass.ps = r.recorded;
  for (auto _ : state) {
    pass.run(r, v);
    benchmark::ClobberMemory();
  }
  const size_t n = r.recorded.size();
  state.counters["Msamples"] = benchmark::Counter(double(n) * double(state.iterations()) * 1e-6,
                                                  benchmark::Counter::kIsRate);
  state.counters["hits"] = double(n);
  state.counters["shadow_rays"] = double(pass.shadow_rays);
  // Share of the hits per material type (types absent from the scene are left out).
  static const char* const kTypeNames[kShadedMaterialTypeCount] = {"lambert%", "oren_nayar%", "mirror%", "metal%",
                                                                   "glass%",   "thin_glass%",  "plastic%"};
  for (int t = 0; t < kShadedMaterialTypeCount; ++t)
    if (r.per_type[size_t(t)]) state.counters[kTypeNames[t]] = 100.0 * double(r.per_type[size_t(t)]) / double(n);
  // Cross-check against the other variant: the same paths continue, and the light they gather agrees (f and pdf
  // of the SIMD kernels differ from the scalar BSDFs by a few ulps).
  Pass other;
  other.ps = r.recorded;
  other.run(r, v == Variant::Wavefront ? Variant::PerHit : Variant::Wavefront);
  size_t depth_mismatch = 0;
  for (size_t i = 0; i < n; ++i) depth_mismatch += pass.ps.depth[i] != other.ps.depth[i];
  const double rel = std::fabs(pass.contribution - other.contribution) / std::max(1e-30, std::fabs(other.contribution));
  if (depth_mismatch > n / 10000 || rel > 1e-4 || pass.shadow_rays != other.shadow_rays) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "variants disagree: %zu path ends differ, shadow rays %zu vs %zu, light %g vs %g",
                  depth_mismatch, pass.shadow_rays, other.shadow_rays, pass.contribution, other.contribution);
    state.SkipWithError(msg);
  }
}

// ----------------------------------------------------------------------------------------- phase 2 in isolation
// The phase-1 state (BSDFs, wo, light candidates) of every wavefront's queue of type T, captured once.
template <MaterialType T>
const std::vector<ShadeScratch<typename MaterialTraits<T>::Bsdf>>& captured() {
  static const auto* scratches = [] {
    using S = ShadeScratch<typename MaterialTraits<T>::Bsdf>;
    auto* out = new std::vector<S>;
    const Recording& r = *record();
    PathState ps = r.recorded;
    RayQueue next;
    ShadowQueue shadows;
    const ShadeContext ctx{*r.scene, r.rules, r.sampler, ps, r.rays, r.hits, next, shadows};
    std::vector<uint32_t> queue;
    for (size_t begin = 0; begin < ps.size(); begin += kWavefront) {
      queue.clear();
      for (size_t i = begin; i < std::min(ps.size(), begin + kWavefront); ++i)
        if (r.hits.material[i].type == T) queue.push_back(uint32_t(i));
      S sc;
      next.clear();
      shadows.clear();
      shade_queue<T>(ctx, queue, sc);
      if (!sc.lights.empty()) out->push_back(std::move(sc));
    }
    return out;
  }();
  return *scratches;
}

enum class Eval { Scalar, Batch, Kernel };

template <MaterialType T>
void BM_Eval(benchmark::State& state, Eval e) {
  auto scratches = captured<T>();  // a copy: the outputs are overwritten
  size_t candidates = 0;
  for (const auto& sc : scratches) candidates += sc.lights.size();
  // Kernel-only inputs: every queue's candidates gathered once, outside the timed loop.
  struct Soa {
    std::vector<float> a[14];
    std::vector<float> f, pdf;
  };
  std::vector<Soa> soa(scratches.size());
  for (size_t q = 0; q < scratches.size(); ++q) {
    const auto& sc = scratches[q];
    for (const LightCandidate& c : sc.lights) {
      const auto& b = sc.bsdf[c.slot];
      const Vec3f wo = sc.wo_local[c.slot], wi = c.wi_local;
      std::vector<float> v = {wo.x, wo.y, wo.z, wi.x, wi.y, wi.z};
      if constexpr (T == MaterialType::Conductor) {
        for (float x : {b.eta.r, b.eta.g, b.eta.b, b.k.r, b.k.g, b.k.b, b.distrib.alpha_x, b.distrib.alpha_y})
          v.push_back(x);
      } else if constexpr (T == MaterialType::OrenNayar) {
        for (float x : {b.albedo.r, b.albedo.g, b.albedo.b, b.sigma}) v.push_back(x);
      } else {
        for (float x : {b.albedo.r, b.albedo.g, b.albedo.b}) v.push_back(x);
      }
      for (size_t j = 0; j < v.size(); ++j) soa[q].a[j].push_back(v[j]);
    }
    soa[q].f.resize(3 * sc.lights.size());
    soa[q].pdf.resize(sc.lights.size());
  }
  for (auto _ : state) {
    for (size_t q = 0; q < scratches.size(); ++q) {
      auto& sc = scratches[q];
      const size_t n = sc.lights.size();
      if (e == Eval::Scalar) {
        for (size_t k = 0; k < n; ++k) {
          const LightCandidate& c = sc.lights[k];
          const auto& b = sc.bsdf[c.slot];
          sc.f[k] = b.eval(sc.wo_local[c.slot], c.wi_local);
          sc.pdf[k] = b.pdf(sc.wo_local[c.slot], c.wi_local);
        }
      } else if (e == Eval::Batch) {
        eval_batch_simd(sc);
      } else {
        Soa& s = soa[q];
        const EvalDirsSoA dirs{s.a[0].data(), s.a[1].data(), s.a[2].data(),
                               s.a[3].data(), s.a[4].data(), s.a[5].data()};
        if constexpr (T == MaterialType::Conductor) {
          const ConductorParamsSoA p{s.a[6].data(),  s.a[7].data(),  s.a[8].data(),  s.a[9].data(),
                                     s.a[10].data(), s.a[11].data(), s.a[12].data(), s.a[13].data()};
          eval_ggx_conductor_soa(n, dirs, p, s.f.data(), s.pdf.data());
        } else if constexpr (T == MaterialType::OrenNayar) {
          eval_oren_nayar_soa(n, dirs, s.a[6].data(), s.a[7].data(), s.a[8].data(), s.a[9].data(), s.f.data(),
                              s.pdf.data());
        } else {
          eval_lambert_soa(n, dirs, s.a[6].data(), s.a[7].data(), s.a[8].data(), s.f.data(), s.pdf.data());
        }
      }
    }
    benchmark::ClobberMemory();
  }
  state.counters["Msamples"] = benchmark::Counter(double(candidates) * double(state.iterations()) * 1e-6,
                                                  benchmark::Counter::kIsRate);
  state.counters["candidates"] = double(candidates);
  state.counters["queues"] = double(scratches.size());
}

[[maybe_unused]] const bool registered = [] {
  benchmark::RegisterBenchmark("shading/wavefront", BM_Shading, Variant::Wavefront)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("shading/per_hit", BM_Shading, Variant::PerHit)->Unit(benchmark::kMillisecond);
  const std::pair<const char*, Eval> evals[] = {{"scalar", Eval::Scalar}, {"batch", Eval::Batch}, {"kernel", Eval::Kernel}};
  for (const auto& [name, e] : evals) {
    benchmark::RegisterBenchmark((std::string("eval/lambert/") + name).c_str(), BM_Eval<MaterialType::Lambert>, e)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark((std::string("eval/oren_nayar/") + name).c_str(), BM_Eval<MaterialType::OrenNayar>, e)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark((std::string("eval/ggx_conductor/") + name).c_str(), BM_Eval<MaterialType::Conductor>,
                                 e)
        ->Unit(benchmark::kMicrosecond);
  }
  return true;
}();

}  // namespace
