#include "render/vpl.h"

#include <cmath>

#include "core/parallel.h"
#include "core/rng.h"
#include "light/light_emission.h"
#include "render/material_resolve.h"

namespace torte {

namespace {

// Light paths draw from a stateless sampler of their family (seeded from the render's seed and the family),
// under "pixel" indices no image reaches (images have fewer than 2^28 pixels): set s is pixel
// kVplPixelBase + s, path j its sample j, so the paths of a set are stratified (Sobol) in their first dimensions.
constexpr uint32_t kVplPixelBase = 0xf0000000u;
enum LightPathDim : uint32_t { kDimLpLight = 0, kDimLpPosition = 1, kDimLpDirection = 2, kDimLpFirstBounce = 3 };
enum LightBounceDim : uint32_t { kDimLpMix = 0, kDimLpLobe = 1, kDimLpBsdf = 2, kDimLpRoulette = 3, kDimsLpBounce = 4 };
inline uint32_t lp_dim(int depth, LightBounceDim d) {
  return kDimLpFirstBounce + uint32_t(depth) * kDimsLpBounce + d;
}

// A VPL as the light path finds it; VplStore's arrays are filled from these in order.
struct RawVpl {
  SurfaceHit s;
  Vec3f wo;
  Rgb power;
  MaterialRef material;
};

// Calls fn(MaterialTypeTag<T>, bsdf) with the BSDF of leaf material m (type T) at tc: one dispatch.
template <class Fn>
void with_bsdf(const Scene& scene, MaterialRef m, const TextureContext& tc, TransportMode mode, Fn&& fn) {
  dispatch_shaded(m.type, [&](auto t) {
    fn(t, MaterialTraits<t()>::bsdf(scene.materials, scene.textures, m.index, tc, mode));
  });
}

// Traces light path `j` of set `set`, appending its VPLs to `out`; returns the number of rays traced.
uint64_t trace_light_path(const Scene& scene, const RenderSettings& settings, const Sampler& sampler, int set,
                          uint32_t j, std::vector<RawVpl>& out) {
  const uint32_t px = kVplPixelBase + uint32_t(set);
  float pmf, uc;
  const int l = scene.light_selection.sample_discrete(sampler.get_1d(px, j, kDimLpLight), &pmf, &uc);
  if (!(pmf > 0)) return 0;
  EmissionSample es;
  if (!sample_emission(scene, scene.lights[size_t(l)], sampler.get_2d(px, j, kDimLpPosition),
                       sampler.get_2d(px, j, kDimLpDirection), uc, &es))
    return 0;
  Rgb beta = es.weight / pmf;
  const float beta0 = beta.max_component();
  if (!(beta0 > 0) || !beta.is_finite()) return 0;
  Vec3f o = length_squared(es.normal) > 0 ? offset_origin(es.origin, es.normal, es.dir) : es.origin;
  Vec3f d = es.dir;
  // A VPL at bounce `depth` lights paths of depth + 1 scattering events (plus the camera's specular ones).
  const int max_vpl_depth = settings.max_depth - 1;
  const float inv_paths = 1.0f / float(settings.light_paths);
  uint64_t rays = 0;
  for (int depth = 1; depth <= max_vpl_depth; ++depth) {
    Ray ray{o, d, kInfinity};
    Hit hit;
    ++rays;
    if (!scene.intersect(ray, &hit)) break;
    SurfaceHit s = scene.surface(ray, hit);
    const MaterialRef m = resolve_material(scene, scene.material_of(s), s, 0.0f,
                                           sampler.get_1d(px, j, lp_dim(depth, kDimLpMix)),
                                           mix_bits(uint64_t(px) << 32 ^ j ^ (uint64_t(depth) << 56)));
    const Vec3f wo = -d;
    const Frame frame = Frame::from_z(s.ns);
    const Vec3f wo_local = frame.to_local(wo);
    const float cos_g_wo = std::fabs(dot(wo, s.ng));
    if (!(cos_g_wo > 0)) break;
    bool go_on = false;
    with_bsdf(scene, m, texture_context(s, 0), TransportMode::Importance, [&](auto, const auto& bsdf) {
      // Flux through the surface (beta) times |cos_s| / |cos_g| of the arriving direction: the shading-normal
      // correction of the incoming side (Veach 1997, 5.3), so the VPL's outgoing radiance uses f * |cos_s|.
      if (bsdf.has_non_specular())
        out.push_back({s, wo, beta * (std::fabs(wo_local.z) / cos_g_wo * inv_paths), m});
      if (depth == max_vpl_depth) return;
      BsdfSample bs;
      const float u_lobe = sampler.get_1d(px, j, lp_dim(depth, kDimLpLobe));
      if (!bsdf.sample(wo_local, u_lobe, sampler.get_2d(px, j, lp_dim(depth, kDimLpBsdf)), &bs) || !(bs.pdf > 0))
        return;
      const Vec3f wi = frame.to_world(bs.wi);
      if (!consistent_sides(s.ng, wo, wi, wo_local, bs.wi)) return;
      // Importance transport with shading normals: f |cos_s(wi)| / pdf times |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|).
      const float cos_s_wi = std::fabs(bs.wi.z);
      if (!(cos_s_wi > 0)) return;
      beta = beta * bs.weight() * (std::fabs(wo_local.z) * std::fabs(dot(wi, s.ng)) / (cos_g_wo * cos_s_wi));
      // Roulette on weak VPL paths: below vpl_roulette of the emitted throughput, continue with probability
      // relative / vpl_roulette, so survivors carry about vpl_roulette of it.
      const float relative = beta.max_component() / beta0;
      if (settings.vpl_roulette > 0 && relative < settings.vpl_roulette) {
        const float q = relative / settings.vpl_roulette;
        if (!(sampler.get_1d(px, j, lp_dim(depth, kDimLpRoulette)) < q)) return;
        beta = beta / q;
      }
      if (!beta.is_finite() || beta.is_black()) return;
      o = offset_origin(s.p, s.ng, wi);
      d = wi;
      go_on = true;
    });
    if (!go_on) break;
  }
  return rays;
}

}  // namespace

VplStore generate_vpls(const Scene& scene, const RenderSettings& settings, uint32_t first_family, int families) {
  VplStore store;
  store.sets = settings.vpl_sets;
  store.first_family = first_family;
  const int sets = settings.vpl_sets * families;  // all sets of all families, family-major
  const float r = scene.radius();
  store.g_max = r > 0 ? settings.g_limit / (r * r) : kInfinity;
  store.set_begin.assign(size_t(sets) + 1, 0);
  if (scene.lights.empty() || settings.max_depth < 2) return store;

  // Sets are independent: trace them in parallel into their own arrays, then concatenate in set order. Each
  // family has its own sampler seed, so families are independent draws.
  std::vector<Sampler> samplers;
  for (int f = 0; f < families; ++f)
    samplers.emplace_back(mix_bits(settings.seed ^ (uint64_t(first_family + uint32_t(f)) + 1) * 0x9e3779b97f4a7c15ull));
  std::vector<std::vector<RawVpl>> raw(static_cast<size_t>(sets));
  std::vector<uint64_t> rays(static_cast<size_t>(sets), 0);
  // --stats: one clock pair per set (its light paths), summed over threads; then the serial concatenation.
  std::vector<double> seconds(settings.stage_stats ? size_t(sets) : 0, 0.0);
  parallel_for(0, sets, [&](int set) {
    StageClock clock(settings.stage_stats);
    clock.start();
    const Sampler& sampler = samplers[size_t(set / settings.vpl_sets)];
    for (uint32_t j = 0; j < uint32_t(settings.light_paths); ++j)
      rays[size_t(set)] +=
          trace_light_path(scene, settings, sampler, set % settings.vpl_sets, j, raw[size_t(set)]);
    StageTime t;
    clock.lap(t, 0);
    if (settings.stage_stats) seconds[size_t(set)] = t.seconds;
  });
  StageClock concatenation(settings.stage_stats);
  concatenation.start();

  size_t total = 0;
  for (const auto& v : raw) total += v.size();
  store.p.reserve(total);
  for (int set = 0; set < sets; ++set) {
    store.light_rays += rays[size_t(set)];
    for (const RawVpl& v : raw[size_t(set)]) {
      const Frame frame = Frame::from_z(v.s.ns);
      store.p.push_back(v.s.p);
      store.ng.push_back(v.s.ng);
      store.ns.push_back(v.s.ns);
      store.wo.push_back(v.wo);
      store.wo_local.push_back(frame.to_local(v.wo));
      store.frame.push_back(frame);
      store.uv.push_back(v.s.uv);
      store.power.push_back(v.power);
      store.material.push_back(v.material);
      // The same texture context as at generation: the same BSDF.
      with_bsdf(scene, v.material, texture_context(v.s, 0), TransportMode::Importance, [&](auto t, const auto& b) {
        auto& array = std::get<int(t())>(store.bsdfs);
        store.bsdf.push_back(uint32_t(array.size()));
        array.push_back(b);
      });
    }
    store.set_begin[size_t(set) + 1] = uint32_t(store.p.size());
  }
  if (settings.stage_stats) {
    concatenation.lap(store.profile, 0);
    for (const double s : seconds) store.profile.seconds += s;
    store.profile.calls = uint64_t(sets);
    store.profile.items = store.light_rays;
  }
  return store;
}

}  // namespace torte
