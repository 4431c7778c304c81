// BDPT's subpaths (render/integrator_bdpt.h): their vertices, stored per wavefront, and the per-material-type
// kernel that shades a queue of subpath hits. A subpath is advanced like any path of the wavefront (trace_rays,
// sort_hits, one kernel per material type); what BDPT adds is that every vertex is kept, with the BSDF built
// there (in a pool per material type, so a connection evaluates it through dispatch_shaded, no virtual call)
// and the two area densities its MIS weights need: pdf_fwd (of the subpath producing this vertex) and pdf_rev
// (of the opposite subpath producing it), in pbrt's formulation (Veach 1997, 10.2).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

#include "material/material_traits.h"
#include "render/shade.h"

namespace torte {

// Sampler dimensions of light subpaths: bounce_dim(depth, d) + this. Camera subpaths use bounce_dim itself (below
// 1 + 10001 * kDimsPerBounce < 2^25); the lens and emission dimensions sit at 2^30 and up.
constexpr uint32_t kDimLightSubpathBase = 1u << 25;

enum class BdptVertexKind : uint8_t { Camera, Light, Surface };

/// One vertex of a subpath. Directions are unit and world-space.
struct BdptVertex {
  static constexpr uint32_t kNone = ~0u;
  Vec3f p;
  Vec3f ng;         // geometric normal; 0 for point and spot lights and the camera (not on a surface)
  Vec3f ns;         // shading normal (surface vertices)
  Vec3f wo;         // towards the previous vertex of the subpath (surface vertices)
  Rgb beta;         // the subpath's throughput arriving here (light subpaths: emitted power over densities)
  float pdf_fwd = 0, pdf_rev = 0;  // area densities: along the subpath, and against it (0 after a delta lobe)
  uint32_t prev = kNone;           // the previous vertex of the same subpath
  uint32_t bsdf = kNone;           // index into the BSDF pool of `type`; kNone: not shaded (cannot connect)
  int32_t light = -1;              // light vertices, and camera-subpath hits on an area light: the light
  float pdf_emit = 0;              // camera-subpath hits on an area light: the area density of emission sampling
  MaterialType type = MaterialType::Lambert;
  BdptVertexKind kind = BdptVertexKind::Surface;
  bool delta = false;        // the subpath left this vertex through a delta lobe
  bool connectible = false;  // a surface with a non-specular lobe
  bool on_surface() const { return ng.x != 0 || ng.y != 0 || ng.z != 0; }
};

/// The area density with which emission sampling (sample_area_light_point) picks hit `s` on area light `light`.
inline float area_light_pdf(const Scene& scene, const Light& light, const SurfaceHit& s) {
  if (light.object < scene.meshes.size()) return 1 / light.area;  // triangles by area, uniform on each
  return pdf_area(scene.quadrics[light.object - scene.meshes.size()], s.uv);
}

/// Converts a solid-angle density at `from` of the direction towards `to` into an area density at `to`.
inline float to_area_density(float pdf_solid, Vec3f from, const BdptVertex& to) {
  const Vec3f d = to.p - from;
  const float d2 = length_squared(d);
  if (!(d2 > 0)) return 0;
  float pdf = pdf_solid / d2;
  if (to.on_surface()) pdf *= std::fabs(dot(to.ng, d)) / std::sqrt(d2);
  return pdf;
}

template <MaterialType T>
using BsdfPool = std::vector<typename MaterialTraits<T>::Bsdf>;

/// The vertices of one wavefront's subpaths (of one direction) and their BSDFs. Vertices are appended as the
/// subpaths advance; a subpath's vertices are chained backwards from last[path]. Capacity only grows to the
/// largest wavefront seen: at most (max_depth + 2) vertices per path (render/integrator_bdpt.h).
struct BdptStore {
  std::vector<BdptVertex> vertices;
  std::vector<uint32_t> last;      // by path: its newest vertex
  std::vector<uint32_t> of_slot;   // by queue slot of the bounce being shaded: its vertex
  PerShadedType<BsdfPool> pools;

  void clear(size_t paths) {
    vertices.clear();
    last.assign(paths, BdptVertex::kNone);
    for_each_shaded_type([&](auto t) { std::get<int(t())>(pools).clear(); });
  }
  uint32_t push(const BdptVertex& v, uint32_t path) {
    BdptVertex& n = vertices.emplace_back(v);
    n.prev = last[path];
    return last[path] = uint32_t(vertices.size() - 1);
  }
  /// Calls fn(bsdf) with the BSDF of surface vertex v (v.bsdf != kNone), through the one type dispatch.
  template <class Fn>
  void with_bsdf(const BdptVertex& v, Fn&& fn) const {
    dispatch_shaded(v.type, [&](auto t) { fn(std::get<int(t())>(pools)[v.bsdf]); });
  }
  /// The vertices of `path`'s subpath, first (the camera or the light) to last, into `out`.
  void chain(uint32_t path, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t v = last[path]; v != BdptVertex::kNone; v = vertices[v].prev) out.push_back(v);
    std::reverse(out.begin(), out.end());
  }
};

/// Records a vertex for every hit of the bounce's rays (after sort_hits: surfaces reconstructed, Mix and Bump
/// resolved) with its throughput and forward density; store.of_slot maps the slots to them. Light subpaths keep
/// the emitted power's scale in filter_weight (as stage_light.h's light paths do): their vertices fold it in.
inline void record_subpath_hits(const Scene& scene, const RayQueue& rays, const HitQueue& hits, const PathState& ps,
                                bool light_subpath, BdptStore& store) {
  store.of_slot.resize(rays.size());
  for (size_t k = 0; k < rays.size(); ++k) {
    store.of_slot[k] = BdptVertex::kNone;
    if (hits.hit[k].prim == kNoHit) continue;
    const uint32_t i = rays.path[k];
    const SurfaceHit& s = hits.surface[k];
    BdptVertex v;
    v.p = s.p;
    v.ng = s.ng;
    v.ns = s.ns;
    v.wo = -rays.dir(k);
    v.beta = light_subpath ? ps.beta[i] * ps.filter_weight[i] : ps.beta[i];
    const BdptVertex& prev = store.vertices[store.last[i]];
    v.pdf_fwd = (ps.flags[i] & kPathSpecular) ? 0.0f : to_area_density(ps.bsdf_pdf[i], prev.p, v);
    if (!light_subpath) {
      v.light = scene.objects[s.object].area_light;
      if (v.light >= 0) v.pdf_emit = area_light_pdf(scene, scene.lights[size_t(v.light)], s);
    }
    store.of_slot[k] = store.push(v, i);
  }
}

/// Shades the subpath hits in `queue` (all of material type T): builds and keeps each BSDF (in `mode`), samples
/// the next direction, sets the vertex's delta flag and the previous vertex's pdf_rev, and continues the path
/// (continue_path: Russian roulette, the adjoint factor for light subpaths) while depth + 1 < depth_limit.
template <MaterialType T>
void shade_subpath_queue(const ShadeContext& ctx, std::span<const uint32_t> queue,
                         ShadeScratch<typename MaterialTraits<T>::Bsdf>& sc, BdptStore& store, TransportMode mode,
                         uint32_t dim_base, int depth_limit) {
  using Traits = MaterialTraits<T>;
  const Scene& scene = ctx.scene;
  const PathState& ps = ctx.paths;
  BsdfPool<T>& pool = std::get<int(T)>(store.pools);
  sc.begin(queue.size());
  for (size_t k = 0; k < queue.size(); ++k) {
    const uint32_t slot = queue[k], i = ctx.rays.path[slot];
    const SurfaceHit& s = ctx.hits.surface[slot];
    const auto& bsdf = sc.bsdf.emplace_back(Traits::bsdf(scene.materials, scene.textures,
                                                         ctx.hits.material[slot].index,
                                                         texture_context(s, ps.footprint[i]), mode));
    sc.frame[k] = Frame::from_z(s.ns);
    sc.wo_local[k] = sc.frame[k].to_local(-ctx.rays.dir(slot));
    BdptVertex& v = store.vertices[store.of_slot[slot]];
    v.type = T;
    v.bsdf = uint32_t(pool.size());
    v.connectible = bsdf.has_non_specular();
    pool.push_back(bsdf);
  }
  for (size_t k = 0; k < queue.size(); ++k) {
    const uint32_t slot = queue[k], i = ctx.rays.path[slot];
    const uint16_t depth = ps.depth[i];
    if (depth + 1 >= depth_limit) continue;
    const uint32_t px = ps.pixel[i], si = ps.sample[i];
    const float uc = Traits::kSingleLobe ? 0.5f : ctx.sampler.get_1d(px, si, dim_base + bounce_dim(depth, kDimBsdfLobe));
    BsdfSample bs;
    if (!sc.bsdf[k].sample(sc.wo_local[k], uc, ctx.sampler.get_2d(px, si, dim_base + bounce_dim(depth, kDimBsdf)),
                           &bs) ||
        !(bs.pdf > 0))
      continue;
    const uint32_t vi = store.of_slot[slot];
    BdptVertex& v = store.vertices[vi];
    v.delta = bs.is_specular();
    // The density of sampling the way back (wi -> wo) at this vertex, as an area density at the previous one.
    const float rev = v.delta ? 0.0f : sc.bsdf[k].pdf(bs.wi, sc.wo_local[k]);
    BdptVertex& prev = store.vertices[v.prev];
    prev.pdf_rev = to_area_density(rev, v.p, prev);
    continue_path(ctx, slot, sc.frame[k], sc.wo_local[k], bs, mode, dim_base);
  }
}

}  // namespace torte
