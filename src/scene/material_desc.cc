#include "scene/material_desc.h"

#include "core/error.h"

namespace torte {

namespace {
template <class T>
MaterialRef push(std::vector<T>& table, MaterialType type, const T& params) {
  table.push_back(params);
  return {type, uint32_t(table.size() - 1)};
}
}  // namespace

RoughnessParams MaterialFlattener::roughness(const RoughnessInput& r) {
  RoughnessParams p;
  p.u = textures_.add(r.u);
  p.v = textures_.add(r.v);
  p.distribution = r.distribution;
  p.remap = r.remap;
  return p;
}

MaterialRef MaterialFlattener::add(const MaterialDesc& d) {
  if (auto it = refs_.find(&d); it != refs_.end()) return it->second;
  MaterialRef ref;
  switch (d.type) {
    case MaterialType::Lambert:
      ref = push(tables_.lambert, d.type, LambertParams{textures_.add(d.color)});
      break;
    case MaterialType::OrenNayar:
      ref = push(tables_.oren_nayar, d.type, OrenNayarParams{textures_.add(d.color), textures_.add(d.sigma)});
      break;
    case MaterialType::Mirror:
      ref = push(tables_.mirror, d.type, MirrorParams{textures_.add(d.color)});
      break;
    case MaterialType::Conductor:
      ref = push(tables_.conductor, d.type,
                 ConductorParams{textures_.add(d.eta_rgb), textures_.add(d.k), roughness(d.roughness)});
      break;
    case MaterialType::Dielectric:
      ref = push(tables_.dielectric, d.type,
                 DielectricParams{textures_.add(d.eta), roughness(d.roughness), textures_.add(d.color),
                                  textures_.add(d.transmit_color)});
      break;
    case MaterialType::ThinDielectric:
      ref = push(tables_.thin_dielectric, d.type,
                 ThinDielectricParams{textures_.add(d.eta), textures_.add(d.color), textures_.add(d.transmit_color)});
      break;
    case MaterialType::CoatedDiffuse:
      ref = push(tables_.coated_diffuse, d.type,
                 CoatedDiffuseParams{textures_.add(d.color), textures_.add(d.eta), roughness(d.roughness)});
      break;
    case MaterialType::Mix: {
      if (!d.a || !d.b) throw Error("internal: mix material without both materials");
      MixParams p{textures_.add(d.amount), add(*d.a), add(*d.b)};
      ref = push(tables_.mix, d.type, p);
      break;
    }
    case MaterialType::Bump: {
      if (!d.a) throw Error("internal: bump material without an inner material");
      BumpParams p{textures_.add(d.height), d.bump_scale, add(*d.a)};
      ref = push(tables_.bump, d.type, p);
      break;
    }
    case MaterialType::Count: throw Error("internal: invalid material type");
  }
  refs_.emplace(&d, ref);
  return ref;
}

}  // namespace torte
