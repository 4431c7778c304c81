// Before hits are sorted by material type, Mix and Bump materials are resolved per hit into a leaf material
// (one with a shading kernel): a Mix picks one of its two materials with probability given by its amount
// texture (stochastic selection, unbiased for the mixture, as pbrt-v4 does), and a Bump perturbs the hit's
// shading normal from its height texture and continues with the wrapped material.
#pragma once
#include <cstdint>
#include <type_traits>

#include "core/rng.h"

#include "scene/scene.h"

namespace torte {

inline TextureContext texture_context(const SurfaceHit& s, float footprint) {
  return {s.p, s.ns, s.uv, s.dpdu, s.dpdv, footprint};
}

// Resolves `ref` at hit `s` (whose shading normal a Bump may change). `first_u` (a number, or a function called
// only when a Mix is met) gives the uniform sample for the first Mix on the way; further ones draw from a hash of `seed` so nested mixes
// stay independent.
template <class FirstU>
MaterialRef resolve_material(const Scene& scene, MaterialRef ref, SurfaceHit& s, float footprint, FirstU&& first_u,
                             uint64_t seed);

// Bump mapping (Blinn 1978, the finite-difference form of pbrt): displaces the surface along the shading normal
// by scale * height(uv) and returns the normal of the displaced surface, on the side of the original one.
Vec3f bump_normal(const Scene& scene, const BumpParams& bump, const SurfaceHit& s, float footprint);

template <class FirstU>
MaterialRef resolve_material(const Scene& scene, MaterialRef ref, SurfaceHit& s, float footprint, FirstU&& first_u,
                             uint64_t seed) {
  const MaterialTables& m = scene.materials;
  bool first = true;
  // A scene's Mix/Bump rows nest at most kMaxMaterialNesting levels (validate_material_tables, run by
  // Scene::finalize), so the loop meets a shaded material at the latest in its last round. An unshaded result
  // would never be shaded, and its path would be traced again and again without end.
  for (int level = 0; level <= kMaxMaterialNesting; ++level) {
    if (ref.type == MaterialType::Mix) {
      const MixParams& mix = m.mix[ref.index];
      const float amount = scene.textures.eval(mix.amount, texture_context(s, footprint));
      float u;
      if (!first) {
        u = float(mix_bits(seed + uint64_t(level) * 0x9e3779b97f4a7c15ull) >> 40) * 0x1p-24f;
      } else if constexpr (std::is_invocable_v<FirstU>) {
        u = float(first_u());
      } else {
        u = float(first_u);  // a plain number works too
      }
      first = false;
      ref = u < amount ? mix.b : mix.a;
    } else if (ref.type == MaterialType::Bump) {
      const BumpParams& bump = m.bump[ref.index];
      s.ns = bump_normal(scene, bump, s, footprint);
      ref = bump.inner;
    } else {
      return ref;
    }
  }
  return ref;
}

}  // namespace torte
