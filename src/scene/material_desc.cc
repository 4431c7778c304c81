#include "scene/material_desc.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "material/material_traits.h"

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

namespace {
std::string nesting_error(int levels) {
  return "the material nests " + std::to_string(levels) + " levels of mix/bump materials; the limit is " +
         std::to_string(kMaxMaterialNesting);
}
}  // namespace

std::shared_ptr<MaterialDesc> make_mix(std::shared_ptr<const MaterialDesc> a, std::shared_ptr<const MaterialDesc> b,
                                       FloatInput amount) {
  if (!a || !b) throw Error("a mix needs both materials");
  const int nesting = 1 + std::max(a->nesting, b->nesting);
  if (nesting > kMaxMaterialNesting) throw Error(nesting_error(nesting));
  auto m = std::make_shared<MaterialDesc>();
  m->type = MaterialType::Mix;
  m->a = std::move(a);
  m->b = std::move(b);
  m->amount = std::move(amount);
  m->nesting = nesting;
  return m;
}

std::shared_ptr<MaterialDesc> make_normal_map(std::shared_ptr<const MaterialDesc> inner, ColorInput map, float scale) {
  auto m = make_bump(std::move(inner), {}, scale);
  m->normal_map = std::move(map);
  m->normal_mapped = true;
  return m;
}

std::shared_ptr<MaterialDesc> make_bump(std::shared_ptr<const MaterialDesc> inner, FloatInput height, float scale) {
  if (!inner) throw Error("a bump needs the material it wraps");
  const int nesting = 1 + inner->nesting;
  if (nesting > kMaxMaterialNesting) throw Error(nesting_error(nesting));
  auto m = std::make_shared<MaterialDesc>();
  m->type = MaterialType::Bump;
  m->a = std::move(inner);
  m->height = std::move(height);
  m->bump_scale = scale;
  m->nesting = nesting;
  return m;
}

void validate_material_tables(const MaterialTables& m) {
  const size_t sizes[kMaterialTypeCount] = {m.lambert.size(),         m.oren_nayar.size(), m.mirror.size(),
                                            m.conductor.size(),       m.dielectric.size(), m.thin_dielectric.size(),
                                            m.coated_diffuse.size(),  m.mix.size(),        m.bump.size()};
  auto check = [&](MaterialRef r) {
    if (int(r.type) >= kMaterialTypeCount || r.index >= sizes[int(r.type)])
      throw Error("internal: a mix or bump material refers to a missing material");
  };
  for (const MixParams& p : m.mix) check(p.a), check(p.b);
  for (const BumpParams& p : m.bump) check(p.inner);
  // Nesting levels by relaxation (-1 = not known yet): after pass k every row nesting at most k + 1 levels is
  // known, so rows still unknown after kMaxMaterialNesting passes nest deeper, or in a cycle.
  std::vector<int> mix_level(m.mix.size(), -1), bump_level(m.bump.size(), -1);
  auto level = [&](MaterialRef r) {
    return r.type == MaterialType::Mix ? mix_level[r.index] : r.type == MaterialType::Bump ? bump_level[r.index] : 0;
  };
  auto settle = [&](int& out, int a, int b) {
    if (out >= 0) return false;
    if (a < 0 || b < 0) return true;
    out = 1 + std::max(a, b);
    if (out > kMaxMaterialNesting) throw Error("internal: " + nesting_error(out));
    return false;
  };
  bool pending = true;
  for (int pass = 0; pass < kMaxMaterialNesting && pending; ++pass) {
    pending = false;
    for (size_t i = 0; i < m.mix.size(); ++i)
      pending |= settle(mix_level[i], level(m.mix[i].a), level(m.mix[i].b));
    for (size_t i = 0; i < m.bump.size(); ++i) pending |= settle(bump_level[i], level(m.bump[i].inner), 0);
  }
  if (pending) throw Error("internal: mix/bump materials nest in a cycle or deeper than " + std::to_string(kMaxMaterialNesting) + " levels");
}

MaterialRef MaterialFlattener::add(const MaterialDesc& d, int level) {
  if (auto it = refs_.find(&d); it != refs_.end()) return it->second;
  // Materials made by make_mix/make_bump never get here too deep; this bounds the recursion for any other.
  if (level > kMaxMaterialNesting) throw Error(nesting_error(level));
  MaterialRef ref;
  // The parameter row of a shaded (leaf) type, from the description's fields.
  auto leaf_params = [&](auto t) {
    constexpr MaterialType T = t();
    if constexpr (T == MaterialType::Lambert) return LambertParams{textures_.add(d.color)};
    if constexpr (T == MaterialType::OrenNayar) return OrenNayarParams{textures_.add(d.color), textures_.add(d.sigma)};
    if constexpr (T == MaterialType::Mirror) return MirrorParams{textures_.add(d.color)};
    if constexpr (T == MaterialType::Conductor)
      return ConductorParams{textures_.add(d.eta_rgb), textures_.add(d.k), roughness(d.roughness)};
    if constexpr (T == MaterialType::Dielectric)
      return DielectricParams{textures_.add(d.eta), roughness(d.roughness), textures_.add(d.color),
                              textures_.add(d.transmit_color)};
    if constexpr (T == MaterialType::ThinDielectric)
      return ThinDielectricParams{textures_.add(d.eta), textures_.add(d.color), textures_.add(d.transmit_color)};
    if constexpr (T == MaterialType::CoatedDiffuse)
      return CoatedDiffuseParams{textures_.add(d.color), textures_.add(d.eta), roughness(d.roughness)};
  };
  const bool leaf = dispatch_shaded(d.type, [&](auto t) {
    ref = push(MaterialTraits<t()>::params(tables_), d.type, leaf_params(t));
  });
  if (leaf) {
    refs_.emplace(&d, ref);
    return ref;
  }
  switch (d.type) {
    case MaterialType::Mix: {
      if (!d.a || !d.b) throw Error("internal: mix material without both materials");
      MixParams p{textures_.add(d.amount), add(*d.a, level + 1), add(*d.b, level + 1)};
      ref = push(tables_.mix, d.type, p);
      break;
    }
    case MaterialType::Bump: {
      if (!d.a) throw Error("internal: bump material without an inner material");
      BumpParams p{textures_.add(d.height), d.bump_scale, add(*d.a, level + 1)};
      if (d.normal_mapped) {
        p.normal_mapped = true;
        p.normal_map = textures_.add(d.normal_map);
      }
      ref = push(tables_.bump, d.type, p);
      break;
    }
    default: throw Error("internal: invalid material type");
  }
  refs_.emplace(&d, ref);
  return ref;
}

}  // namespace torte
