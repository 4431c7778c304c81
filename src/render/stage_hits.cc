#include "render/stage_hits.h"

#include <new>

#include "core/rng.h"
#include "render/material_resolve.h"
#include "render/shade.h"

namespace torte {

void sort_hits(const Scene& scene, const TransportRules& rules, const Sampler& sampler, float spread,
               const RayQueue& rays, HitQueue& hits, PathState& ps, MaterialQueues& out, uint32_t dim_base) {
  uint32_t counts[kMaterialTypeCount] = {};
  const size_t n = rays.size();
  out.unsorted.resize(n);
  // Surfaces first, in a loop of their own: a reconstruction is a chain of latencies (vertex loads, a square root,
  // a division) that the core overlaps across hits only when little else sits between them.
  for (size_t k = 0; k < n; ++k) {
    const Hit& hit = hits.hit[k];
    if (hit.prim == kNoHit) continue;
    // Built in place (a prvalue initialising the slot): assigning the returned hit would copy it through the stack,
    // and those loads of just-stored fields stall store forwarding, once per hit.
    ::new (static_cast<void*>(&hits.surface[k])) SurfaceHit(scene.surface(Ray{rays.origin(k), rays.dir(k), hit.t}, hit));
  }
  size_t kept = 0;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = rays.path[k];
    const Hit& hit = hits.hit[k];
    if (hit.prim == kNoHit) continue;
    SurfaceHit& s = hits.surface[k];
    // `direct` follows specular chains only: a non-specular sample just looks for emission at its next hit.
    if (ps.depth[i] >= rules.max_depth || (rules.specular_chains_only && (ps.flags[i] & kPathScattered))) continue;
    ps.footprint[i] += spread * hit.t;  // ray-cone width at the hit
    const uint32_t px = ps.pixel[i], si = ps.sample[i];
    // Voxel faces and cell shapes carry their own material (SurfaceHit::material, -1 = the object's).
    const MaterialRef m = resolve_material(
        scene, scene.material_of(s), s, ps.footprint[i],
        [&] { return sampler.get_1d(px, si, dim_base + bounce_dim(ps.depth[i], kDimMaterialMix)); },
        mix_bits((uint64_t(px) << 32 | si) ^ (uint64_t(ps.depth[i]) << 56) ^ dim_base));
    hits.material[k] = m;
    ++counts[int(m.type)];
    out.unsorted[kept++] = uint32_t(k);
  }

  // Counting sort of the surviving slots by material type: one contiguous queue per type. The kept slots sit
  // in out.unsorted[0, kept) in queue order.
  out.begin[0] = 0;
  for (int t = 0; t < kMaterialTypeCount; ++t) out.begin[t + 1] = out.begin[t] + counts[t];
  uint32_t cursor[kMaterialTypeCount];
  for (int t = 0; t < kMaterialTypeCount; ++t) cursor[t] = out.begin[t];
  out.slots.resize(kept);
  for (size_t j = 0; j < kept; ++j) {
    const uint32_t k = out.unsorted[j]; out.slots[cursor[int(hits.material[k].type)]++] = k;
  }
}

}  // namespace torte
