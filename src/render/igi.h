// Instant global illumination (Keller 1997; the seed's "igi" renderer), IntegratorKind::Igi.
//
// Preprocess (generate_vpls, once per render): `vpl_sets` independent sets of `light_paths` light paths each. A
// path leaves a light chosen by power (light/light_emission.h) and, at every surface hit whose BSDF has a
// non-specular part, stores a virtual point light (VPL): the hit point, its normals, its resolved material with
// the BSDF built in TransportMode::Importance, the direction wo the light arrived from, and the flux the path
// carries divided by light_paths. The path then continues by BSDF sampling; specular-only surfaces pass the
// light on without storing a VPL (caustics reach the next diffuse hit). Russian roulette ends weak paths
// (RenderSettings::vpl_roulette). Light paths never store a VPL on the light itself, so the VPLs carry light
// that has bounced at least once: their estimate is INDIRECT light only, and direct light stays with the
// camera side's next-event estimation (exactly as `direct`: MIS between light and BSDF sampling, one or all
// lights). Nothing is counted twice.
//
// Rendering: camera paths run as `direct` (following specular chains; ends_after_first_scatter). Every hit
// shaded with a non-specular BSDF also gathers from the VPLs of one set, chosen per pixel sample by interleaved
// sampling ((hash(pixel) + sample) mod vpl_sets): for VPL y seen from x in direction wi,
//   beta * f_x(wo, wi) * min(G, G_max) * f_y(wo_y, -wi) * power_y,   G = |cos_x| |cos_y| / |x - y|^2,
// queued as a shadow ray (ShadowQueue) and traced in batches. G_max = g_limit / R^2 (R: the scene's bounding
// radius). The clamp removes the bright spots VPLs make next to the surfaces they lie on, and with them the
// energy of short-range inter-reflections (corners get darker): the bias, which goes to zero as g_limit grows.
// A VPL at light-path bounce d adds paths of d + 1 scattering events: VPLs are stored for d <= max_depth - 1.
// Missing, as in `direct`: light reaching the first non-specular camera hit through specular surfaces only
// (L S+ D E caustics: no VPL lies on a light). Caustics that bounce once more (L S+ D D E) are in, through the
// VPLs light paths leave behind specular chains. Unclamped (huge g_limit), VPL estimates are heavy-tailed: with
// few light paths the image mean is usually a little low (scenes/lights.lua, light=spot: -1.4 % with 8 x 256
// light paths, -0.3 % with 32 x 1024).
//
// Measured on scenes/cornell-box.lua, 256x256, against path at 1024 spp (errors on images clamped to 1; 2 cores
// shared with other builds, so times are rough; rays are exact):
//   direct 16 spp   0.9 s   2.7 M rays  RMSE 0.041  (no indirect light: mean abs error 0.028)
//   path   16 spp   2.4 s   4.9 M rays  RMSE 0.015     path 64 spp   9.4 s  19.5 M rays  RMSE 0.0067
//   igi     4 spp   7.2 s  31.1 M rays  RMSE 0.013     igi 16 spp   23.9 s 124.4 M rays  RMSE 0.0067
//   igi 16 spp, light_paths=16: 8.4 s, 35.4 M rays, RMSE 0.0095; g_limit 2 / 200 at 16 spp: RMSE 0.011 / 0.0078.
// igi's error is smooth (no pixel noise) but at equal time path tracing is as accurate or better here: each
// camera hit pays one shadow ray per VPL of its set (~120 with the defaults).
#pragma once
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "render/shade.h"

namespace torte {

// The VPLs of all sets, structure of arrays; set s is [set_begin[s], set_begin[s + 1]).
struct VplStore {
  std::vector<Vec3f> p, ng, ns;       // position, geometric and shading normal
  std::vector<Vec3f> wo;              // unit, towards where the light came from (world)
  std::vector<Vec3f> wo_local;        // the same in the shading frame
  std::vector<Frame> frame;           // shading frame (z = ns)
  std::vector<Vec2f> uv;              // surface parameters of the hit (the BSDF below was built from them)
  std::vector<Rgb> power;             // flux / light_paths, with the shading-normal correction for wo folded in
  std::vector<MaterialRef> material;  // resolved leaf material (Mix and Bump resolved at generation)
  std::vector<uint32_t> bsdf;         // index into the BSDF array of material[v].type
  std::vector<uint32_t> set_begin;    // vpl_sets + 1 offsets
  // The VPLs' BSDFs, built once (texture lookups at generation), one array per shaded material type.
  template <MaterialType T>
  using BsdfArray = std::vector<typename MaterialTraits<T>::Bsdf>;
  PerShadedType<BsdfArray> bsdfs;
  float g_max = kInfinity;  // absolute clamp of the geometry term
  uint64_t light_rays = 0;  // rays traced to build the VPLs

  size_t size() const { return p.size(); }
  int set_count() const { return int(set_begin.size()) - 1; }
  // The set a camera sample gathers from: interleaved, so each pixel cycles through all sets.
  uint32_t set_of(uint32_t pixel, uint32_t sample, uint64_t seed) const {
    return uint32_t((mix_bits(uint64_t(pixel) ^ (seed << 32)) + sample) % uint64_t(set_count()));
  }
  // f of VPL v for light leaving towards w (world, unit), in importance mode: f_v(wo_v, w). 0 when w is on the
  // wrong side of the surface for the normals. One dispatch on the material type, no virtual call.
  Rgb eval(uint32_t v, Vec3f w) const {
    const Vec3f wl = frame[v].to_local(w);
    if (!consistent_sides(ng[v], wo[v], w, wo_local[v], wl)) return {};
    Rgb f;
    dispatch_shaded(material[v].type, [&](auto t) { f = std::get<int(t())>(bsdfs)[bsdf[v]].eval(wo_local[v], wl); });
    return f;
  }
};

// Traces the light paths and builds the VPLs (TBB over sets; deterministic for a seed, any thread count).
VplStore generate_vpls(const Scene& scene, const RenderSettings& settings);

// Gathers VPL light at the hits of material type T recorded by shade_queue<T> (their BSDFs, frames and local
// wo are still in `sc`): one shadow ray per (hit, VPL of its set) into `shadows`, calling flush() whenever the
// queue holds kVplShadowBatch rays or more, so memory stays bounded for any number of VPLs. Rays are queued VPL
// by VPL over the hits that use its set (hits of a tile, towards one point): runs of coherent shadow rays,
// which the caller traces as packets. `order` is scratch.
constexpr size_t kVplShadowBatch = size_t(1) << 16;

template <MaterialType T, class Flush>
void gather_vpls(const VplStore& vpls, const ShadeScratch<typename MaterialTraits<T>::Bsdf>& sc,
                 std::span<const VplHit> hits, const PathState& ps, uint64_t seed, ShadowQueue& shadows,
                 std::vector<uint32_t>& order, Flush&& flush) {
  if (vpls.size() == 0 || hits.empty()) return;
  // Counting sort of the hits by the set they gather from.
  const int sets = vpls.set_count();
  std::vector<uint32_t> begin(size_t(sets) + 1, 0);
  for (const VplHit& h : hits) ++begin[vpls.set_of(ps.pixel[h.path], ps.sample[h.path], seed) + 1];
  for (int s = 0; s < sets; ++s) begin[size_t(s) + 1] += begin[size_t(s)];
  order.resize(hits.size());
  {
    std::vector<uint32_t> cursor(begin.begin(), begin.end() - 1);
    for (uint32_t k = 0; k < uint32_t(hits.size()); ++k)
      order[cursor[vpls.set_of(ps.pixel[hits[k].path], ps.sample[hits[k].path], seed)]++] = k;
  }
  for (int set = 0; set < sets; ++set) {
    for (uint32_t v = vpls.set_begin[size_t(set)]; v < vpls.set_begin[size_t(set) + 1]; ++v) {
      for (uint32_t o_k = begin[size_t(set)]; o_k < begin[size_t(set) + 1]; ++o_k) {
        const VplHit& h = hits[order[o_k]];
        const SurfaceHit& s = ps.surface[h.path];
        const Frame& frame = sc.frame[h.slot];
        const Vec3f wo_local = sc.wo_local[h.slot];
        const Vec3f d = vpls.p[v] - s.p;
        const float d2 = length_squared(d);
        if (!(d2 > 0)) continue;
        const Vec3f wi = d / std::sqrt(d2);
        const Vec3f wi_local = frame.to_local(wi);
        if (!consistent_sides(s.ng, frame.to_world(wo_local), wi, wo_local, wi_local)) continue;
        const float g = std::min(std::fabs(wi_local.z) * std::fabs(dot(vpls.ng[v], wi)) / d2, vpls.g_max);
        const Rgb fx = sc.bsdf[h.slot].eval(wo_local, wi_local);
        if (fx.is_black() || !(g > 0)) continue;
        const Rgb fy = vpls.eval(v, -wi);
        const Rgb c = h.beta * fx * fy * vpls.power[v] * g;
        if (c.is_black()) continue;
        // From just off x to just off y (each offset on the side facing the other point).
        const Vec3f o = offset_origin(s.p, s.ng, wi);
        const Vec3f to = offset_origin(vpls.p[v], vpls.ng[v], -wi) - o;
        const float len = length(to);
        if (!(len > 0)) continue;
        shadows.push(o, to / len, len * (1 - 1e-4f), c, h.path);
      }
      if (shadows.size() >= kVplShadowBatch) flush();
    }
  }
}

}  // namespace torte
