// Virtual point lights for IGI (render/integrator_igi.h): light paths traced from the lights leave a VPL at
// every non-specular hit; camera hits then gather from the VPLs of one set, one shadow ray per VPL.
//
// VPLs come in families, one per camera sample index: the camera sample (pixel, s) gathers from one of the
// vpl_sets sets of family s, chosen by interleaving ((hash(pixel) + s) mod vpl_sets), so neighbouring pixels
// use different sets and every sample of a pixel uses VPLs drawn independently of its other samples. The
// estimate is then consistent in the sample count: the VPL error falls as 1/sqrt(spp) like the rest, towards
// the clamped solution. A progressive pass generates the families of the sample indices it renders.
#pragma once
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "core/rng.h"
#include "render/render_settings.h"
#include "render/shade.h"

namespace torte {

// The VPLs of the families of a pass, structure of arrays; set s of family f (relative to first_family) is
// [set_begin[f * sets + s], set_begin[f * sets + s + 1]).
struct VplStore {
  std::vector<Vec3f> p, ng, ns;       // position, geometric and shading normal
  std::vector<Vec3f> wo;              // unit, towards where the light came from (world)
  std::vector<Vec3f> wo_local;        // the same in the shading frame
  std::vector<Frame> frame;           // shading frame (z = ns)
  std::vector<Vec2f> uv;              // surface parameters of the hit (the BSDF below was built from them)
  std::vector<Rgb> power;             // flux / light_paths, with the shading-normal correction for wo folded in
  std::vector<MaterialRef> material;  // resolved leaf material (Mix and Bump resolved at generation)
  std::vector<uint32_t> bsdf;         // index into the BSDF array of material[v].type
  std::vector<uint32_t> set_begin;    // families * sets + 1 offsets
  int sets = 1;                       // sets per family
  uint32_t first_family = 0;          // the sample index of family 0
  // The VPLs' BSDFs, built once (texture lookups at generation), one array per shaded material type.
  template <MaterialType T>
  using BsdfArray = std::vector<typename MaterialTraits<T>::Bsdf>;
  PerShadedType<BsdfArray> bsdfs;
  float g_max = kInfinity;  // absolute clamp of the geometry term
  uint64_t light_rays = 0;  // rays traced to build the VPLs
  StageTime profile;        // with RenderSettings::stage_stats: thread seconds, sets and light rays of the build

  size_t size() const { return p.size(); }
  int set_count() const { return int(set_begin.size()) - 1; }
  // The set a camera sample gathers from (an index into set_begin): in its sample's family, interleaved over
  // pixels so that neighbours use different sets.
  uint32_t set_of(uint32_t pixel, uint32_t sample, uint64_t seed) const {
    const uint32_t in_family = uint32_t((mix_bits(uint64_t(pixel) ^ (seed << 32)) + sample) % uint64_t(sets));
    return (sample - first_family) * uint32_t(sets) + in_family;
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

// Traces the light paths of the families of sample indices [first_family, first_family + families) and builds
// their VPLs (TBB over sets; deterministic for a seed, any thread count).
VplStore generate_vpls(const Scene& scene, const RenderSettings& settings, uint32_t first_family, int families);

// A camera hit that gathers from the VPLs: its slot in its type's shading queue (for the BSDF and frame left in
// the type's ShadeScratch), its ray-queue slot (for the surface), its path and the throughput at the hit.
struct VplHit {
  uint32_t slot, ray, path;
  Rgb beta;
};

// Gathers VPL light at the hits of material type T recorded after shade_queue<T> (their BSDFs, frames and local
// wo are still in `sc`): one shadow ray per (hit, VPL of its set) into `shadows`, calling flush() whenever the
// queue holds kVplShadowBatch rays or more, so memory stays bounded for any number of VPLs. Rays are queued VPL
// by VPL over the hits that use its set (hits of a tile, towards one point): runs of coherent shadow rays,
// which the caller traces as packets. `order` and `begin` are scratch.
constexpr size_t kVplShadowBatch = size_t(1) << 16;

template <MaterialType T, class Flush>
void gather_vpls(const VplStore& vpls, const ShadeScratch<typename MaterialTraits<T>::Bsdf>& sc,
                 std::span<const VplHit> hits, const PathState& ps, const HitQueue& hq, uint64_t seed,
                 ShadowQueue& shadows, std::vector<uint32_t>& order, std::vector<uint32_t>& begin, Flush&& flush) {
  if (vpls.size() == 0 || hits.empty()) return;
  // Counting sort of the hits by the set they gather from.
  const int sets = vpls.set_count();
  begin.assign(size_t(sets) + 1, 0);
  for (const VplHit& h : hits) ++begin[vpls.set_of(ps.pixel[h.path], ps.sample[h.path], seed) + 1];
  for (int s = 0; s < sets; ++s) begin[size_t(s) + 1] += begin[size_t(s)];
  order.resize(hits.size());
  {
    std::vector<uint32_t> cursor(begin.begin(), begin.end() - 1);
    for (uint32_t k = 0; k < uint32_t(hits.size()); ++k)
      order[cursor[vpls.set_of(ps.pixel[hits[k].path], ps.sample[hits[k].path], seed)]++] = k;
  }
  for (int set = 0; set < sets; ++set) {
    if (begin[size_t(set)] == begin[size_t(set) + 1]) continue;
    for (uint32_t v = vpls.set_begin[size_t(set)]; v < vpls.set_begin[size_t(set) + 1]; ++v) {
      for (uint32_t o_k = begin[size_t(set)]; o_k < begin[size_t(set) + 1]; ++o_k) {
        const VplHit& h = hits[order[o_k]];
        const SurfaceHit& s = hq.surface[h.ray];
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
