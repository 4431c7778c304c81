// An independent per-hit reference for the wavefront renderer: a recursive single-ray path tracer (next-event
// estimation + BSDF sampling combined with the power heuristic, Russian roulette) that traces one ray at a time
// through Scene::intersect / Scene::occluded and dispatches materials PER HIT through a virtual interface
// wrapping MaterialTraits<T>::bsdf — the "previous per-hit path". It shares with the renderer only the scene,
// the BSDFs and lights (what it is meant to check the wavefront plumbing against), not the sampler (it draws
// from Pcg32), the queues, the sorting or the SIMD evaluation.
//
// Also used by bench/bench_shading.cc as the per-hit virtual-dispatch baseline (reference::PerHitBsdf).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <new>
#include <vector>

#include "camera/camera.h"
#include "core/rng.h"
#include "core/parallel.h"
#include "core/sampling.h"
#include "film/image.h"
#include "material/material_traits.h"
#include "render/material_resolve.h"
#include "render/render.h"
#include "scene/scene.h"

namespace torte::reference {

// The per-hit material interface: one virtual call per BSDF operation.
class BsdfInterface {
 public:
  virtual ~BsdfInterface() = default;
  virtual Rgb eval(Vec3f wo, Vec3f wi) const = 0;
  virtual float pdf(Vec3f wo, Vec3f wi) const = 0;
  virtual bool sample(Vec3f wo, float uc, Vec2f u, BsdfSample* s) const = 0;
  virtual bool has_non_specular() const = 0;
};

template <class B>
class BsdfAdapter final : public BsdfInterface {
 public:
  BsdfAdapter(const B& b, float scale) : b_(b), scale_(scale) {}
  Rgb eval(Vec3f wo, Vec3f wi) const override { return b_.eval(wo, wi) * scale_; }
  float pdf(Vec3f wo, Vec3f wi) const override { return b_.pdf(wo, wi); }
  bool sample(Vec3f wo, float uc, Vec2f u, BsdfSample* s) const override {
    if (!b_.sample(wo, uc, u, s)) return false;
    s->f = s->f * scale_;
    return true;
  }
  bool has_non_specular() const override { return b_.has_non_specular(); }

 private:
  B b_;
  float scale_;
};

// Test hook: multiplies the BSDF values (eval and sampled f) of one material type, so that tests can check that
// a wrong BSDF is detected. scaled_type = Count leaves everything alone.
struct Options {
  MaterialType scaled_type = MaterialType::Count;
  float scale = 1;
};

// Holds the BSDF of one hit in place (no allocation per hit), behind the virtual interface.
class PerHitBsdf {
 public:
  PerHitBsdf() = default;
  PerHitBsdf(const PerHitBsdf&) = delete;
  PerHitBsdf& operator=(const PerHitBsdf&) = delete;
  ~PerHitBsdf() { reset(); }

  // Builds the BSDF of material `m` at the hit (a leaf type: Mix and Bump are resolved before).
  const BsdfInterface& build(const Scene& scene, MaterialRef m, const TextureContext& tc, const Options& opt = {}) {
    reset();
    switch (m.type) {
      case MaterialType::Lambert: return make<MaterialType::Lambert>(scene, m, tc, opt);
      case MaterialType::OrenNayar: return make<MaterialType::OrenNayar>(scene, m, tc, opt);
      case MaterialType::Mirror: return make<MaterialType::Mirror>(scene, m, tc, opt);
      case MaterialType::Conductor: return make<MaterialType::Conductor>(scene, m, tc, opt);
      case MaterialType::Dielectric: return make<MaterialType::Dielectric>(scene, m, tc, opt);
      case MaterialType::ThinDielectric: return make<MaterialType::ThinDielectric>(scene, m, tc, opt);
      case MaterialType::CoatedDiffuse: return make<MaterialType::CoatedDiffuse>(scene, m, tc, opt);
      default: break;
    }
    return make<MaterialType::Lambert>(scene, m, tc, opt);  // unreachable for resolved materials
  }

 private:
  template <MaterialType T>
  const BsdfInterface& make(const Scene& scene, MaterialRef m, const TextureContext& tc, const Options& opt) {
    using B = typename MaterialTraits<T>::Bsdf;
    static_assert(sizeof(BsdfAdapter<B>) <= sizeof(storage_), "PerHitBsdf storage too small");
    const float scale = opt.scaled_type == T ? opt.scale : 1.0f;
    live_ = new (storage_) BsdfAdapter<B>(MaterialTraits<T>::bsdf(scene.materials, scene.textures, m.index, tc, TransportMode::Radiance), scale);
    return *live_;
  }
  void reset() {
    if (live_) live_->~BsdfInterface();
    live_ = nullptr;
  }
  alignas(std::max_align_t) std::byte storage_[256];
  BsdfInterface* live_ = nullptr;
};

struct PixelEstimate {
  Rgb mean;           // filter-weighted mean of the samples
  Rgb var_of_mean;    // variance of that mean, from the sample spread
};

class PathTracer {
 public:
  PathTracer(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings, Options opt = {})
      : scene_(scene), camera_(camera), settings_(settings), opt_(opt) {}

  // Radiance along `ray` (the camera ray of a path). Recursive: one call per path vertex.
  Rgb radiance(const Ray& ray, Pcg32& rng) const { return li(ray, 0, true, 0, Rgb(1), 1, rng); }

  // Every pixel at `spp` samples (filter importance sampled like the renderer), in parallel over rows.
  std::vector<PixelEstimate> render(int spp, uint64_t seed) const {
    const Camera camera(camera_, settings_.width, settings_.height);
    std::vector<PixelEstimate> out(size_t(settings_.width) * settings_.height);
    parallel_for(0, settings_.height, [&](int y) {
      for (int x = 0; x < settings_.width; ++x) {
        const uint32_t pixel = uint32_t(y * settings_.width + x);
        Pcg32 rng(mix_bits(seed * 0x9e3779b97f4a7c15ULL + pixel), pixel);
        double sw = 0, s[3] = {}, s2[3] = {};
        for (int k = 0; k < spp; ++k) {
          const Filter::Sample fs = settings_.filter.sample({rng.next_float(), rng.next_float()});
          const Ray ray = camera.generate_ray({float(x) + 0.5f + fs.offset.x, float(y) + 0.5f + fs.offset.y});
          const Rgb L = radiance(ray, rng);
          if (!L.is_finite()) continue;
          const double v[3] = {L.r, L.g, L.b};
          sw += fs.weight;
          for (int c = 0; c < 3; ++c) {
            s[c] += fs.weight * v[c];
            s2[c] += double(fs.weight) * fs.weight * v[c] * v[c];
          }
        }
        PixelEstimate& e = out[pixel];
        if (sw == 0) continue;
        float m[3], var[3];
        for (int c = 0; c < 3; ++c) {
          const double mean = s[c] / sw;
          m[c] = float(mean);
          // Samples y_k = w_k L_k / (sum w / n): variance of their mean.
          const double n = spp, scale = n / sw;
          const double ey = s[c] * scale / n, ey2 = s2[c] * scale * scale / n;
          var[c] = float(std::max(0.0, ey2 - ey * ey) / n);
        }
        e.mean = {m[0], m[1], m[2]};
        e.var_of_mean = {var[0], var[1], var[2]};
      }
    });
    return out;
  }

 private:
  // Radiance arriving along `ray` at the path's depth-th vertex. `specular` is true for camera rays and rays
  // leaving delta lobes (emission then gets MIS weight 1); `bsdf_pdf` is the pdf of the BSDF sample that made
  // the ray; `beta` and `eta_scale` the throughput so far (for Russian roulette only).
  Rgb li(const Ray& ray_in, int depth, bool specular, float bsdf_pdf, Rgb beta, float eta_scale, Pcg32& rng) const {
    const Scene& scene = scene_;
    Ray ray = ray_in;
    Hit hit;
    Rgb L;
    auto emission_weight = [&](int light_index, float light_pdf_sa) {
      if (specular) return 1.0f;
      const float pmf = scene.light_selection.pmf(light_index);
      return power_heuristic(1, bsdf_pdf, 1, pmf * light_pdf_sa);
    };
    if (!scene.intersect(ray, &hit)) {
      for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!is_infinite_light(light)) continue;
        L += escaped_radiance(light, ray_in.d) * emission_weight(int(l), light_pdf(scene, light, ray_in.o, ray_in.d, nullptr, kInfinity));
      }
      return L;
    }
    SurfaceHit s = scene.surface(Ray{ray_in.o, ray_in.d, hit.t}, hit);
    const SceneObject& object = scene.objects[s.object];
    if (object.area_light >= 0) {
      const Light& light = scene.lights[size_t(object.area_light)];
      const Rgb le = area_emission(scene, light, s, ray_in.d);
      if (!le.is_black())
        L += le * emission_weight(object.area_light, light_pdf(scene, light, ray_in.o, ray_in.d, &s, hit.t));
    }
    if (depth >= settings_.max_depth) return L;

    const uint64_t mix_seed = rng.next_u32();
    const MaterialRef m =
        resolve_material(scene, scene.material_of(s), s, 0.0f, [&rng] { return rng.next_float(); }, mix_seed);
    PerHitBsdf holder;
    const BsdfInterface& bsdf = holder.build(scene, m, texture_context(s, 0.0f), opt_);
    const Frame frame = Frame::from_z(s.ns);
    const Vec3f wo = -ray_in.d, wo_local = frame.to_local(wo);
    auto consistent = [&](Vec3f wi, Vec3f wi_local) {
      return (dot(wo, s.ng) * dot(wi, s.ng) > 0) == (wo_local.z * wi_local.z > 0);
    };

    // Next-event estimation: one light chosen by power.
    if (bsdf.has_non_specular() && !scene.lights.empty()) {
      float pmf = 0;
      const int l = scene.light_selection.sample_discrete(rng.next_float(), &pmf);
      const Vec2f u{rng.next_float(), rng.next_float()};
      LightSample ls;
      if (pmf > 0 && sample_light(scene, scene.lights[size_t(l)], s.p, u, &ls)) {
        const Vec3f wi_local = frame.to_local(ls.wi);
        const float lpdf = pmf * ls.pdf;
        if (consistent(ls.wi, wi_local) && lpdf > 0) {
          const Rgb f = bsdf.eval(wo_local, wi_local) * std::fabs(wi_local.z);
          if (!f.is_black()) {
            const Vec3f o = offset_origin(s.p, s.ng, ls.wi);
            const Ray shadow = ls.distance == kInfinity ? Ray{o, ls.wi, kInfinity}
                                                        : ray_towards(o, s.p + ls.wi * ls.distance, ls.wi, 1e-4f);
            if (!scene.occluded(shadow)) {
              const float w = ls.delta ? 1.0f : power_heuristic(1, lpdf, 1, bsdf.pdf(wo_local, wi_local));
              L += f * ls.radiance * (w / lpdf);
            }
          }
        }
      }
    }

    // BSDF sampling, then recursion.
    BsdfSample bs;
    const float uc = rng.next_float();
    const Vec2f u{rng.next_float(), rng.next_float()};
    if (!bsdf.sample(wo_local, uc, u, &bs) || !(bs.pdf > 0)) return L;
    const Vec3f wi = frame.to_world(bs.wi);
    if (!consistent(wi, bs.wi)) return L;
    Rgb weight = bs.weight();
    if (bs.is_transmission()) eta_scale *= bs.eta * bs.eta;
    if (depth + 1 >= settings_.rr_depth) {
      const float q = std::min(0.95f, (beta * weight * eta_scale).max_component());
      if (!(rng.next_float() < q)) return L;
      weight = weight / q;
    }
    const Ray next{offset_origin(s.p, s.ng, wi), wi, kInfinity};
    L += weight * li(next, depth + 1, bs.is_specular(), bs.pdf, beta * weight, eta_scale, rng);
    return L;
  }

  const Scene& scene_;
  CameraDesc camera_;
  const RenderSettings& settings_;
  Options opt_;
};

}  // namespace torte::reference
