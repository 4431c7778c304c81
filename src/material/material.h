// Material types and their parameter tables (scene side). The renderer shades hits in wavefronts: hits are
// counting-sorted by MaterialType and each type's queue is evaluated by one kernel templated on the type (see
// render/shade.h and material/material_traits.h), so there is no virtual call per hit. Mix and Bump are not shaded
// themselves: render/material_resolve.h turns them into one of the leaf types (and a bumped shading normal)
// before the sort.
//
// Adding a shaded material type (everything generic — shading kernels, IGI's VPLs, per-type scratch and queues —
// follows from the type list):
//   1. its BSDF value type in material/<name>.h (eval, pdf, sample, has_non_specular; see material/bsdf.h);
//   2. an enumerator below, before Mix, and a params struct + a vector in MaterialTables;
//   3. the enumerator in ShadedMaterialTypes (material/material_types.h), in enum order;
//   4. MaterialTraits<T> in material/material_traits.h (Bsdf, params, bsdf, kSingleLobe, kBatchEval);
//   5. its description: MaterialDesc fields and the leaf case of MaterialFlattener::add (scene/material_desc.cc),
//      and the Lua constructor in lua/ that fills them;
//   6. tests: a furnace/reciprocity test of the BSDF and a render of tests/material_room.h against the reference.
//
// Parameters are FloatParam/ColorParam: a constant, or a texture in the scene's TextureTable.
#pragma once
#include <cstdint>
#include <vector>

#include "material/microfacet.h"
#include "texture/texture_param.h"

namespace torte {

enum class MaterialType : uint8_t {
  Lambert,        // matte without roughness
  OrenNayar,      // matte with sigma > 0
  Mirror,         // perfect specular reflection, tinted
  Conductor,      // metal: microfacet (or smooth) reflection with complex-IOR Fresnel
  Dielectric,     // glass and rough_glass: Fresnel reflection + refraction, smooth or microfacet (Walter 2007)
  ThinDielectric, // glass{thin=true}: a thin slab, transmission straight through
  CoatedDiffuse,  // plastic: diffuse base under a glossy dielectric coating
  Mix,            // resolved stochastically into one of two materials by a texture
  Bump,           // resolved into its inner material with a perturbed shading normal
  Count
};
constexpr int kMaterialTypeCount = int(MaterialType::Count);
// Types that own a shading kernel (Mix and Bump are resolved before shading).
constexpr int kShadedMaterialTypeCount = int(MaterialType::Mix);
inline bool is_shaded(MaterialType t) { return int(t) < kShadedMaterialTypeCount; }

/// Mix and Bump materials nest at most this many levels above a shaded material (a leaf is level 0, mix{a, b}
/// of two leaves level 1). Materials deeper than this are refused when they are made (scene/material_desc.h) and
/// when a scene's tables are checked (validate_material_tables), so resolve_material always reaches a leaf.
constexpr int kMaxMaterialNesting = 64;

// 8 bytes: which table and which row.
struct MaterialRef {
  MaterialType type = MaterialType::Lambert;
  uint32_t index = 0;
};

// Microfacet roughness along the tangent's u and v. With `remap` (the default from Lua), alpha = roughness^2,
// which spreads the perceptually useful range over [0, 1]; otherwise the values are alpha itself.
struct RoughnessParams {
  FloatParam u, v;
  MicrofacetDistribution::Kind distribution = MicrofacetDistribution::Kind::GGX;
  bool remap = true;
};

struct LambertParams {
  ColorParam albedo{Rgb(0.5f)};
};
struct OrenNayarParams {
  ColorParam albedo{Rgb(0.5f)};
  FloatParam sigma;  // standard deviation of the facet angle, degrees
};
struct MirrorParams {
  ColorParam tint{Rgb(1)};
};
struct ConductorParams {
  ColorParam eta, k;
  RoughnessParams roughness;
};
struct DielectricParams {
  FloatParam eta{1.5f};  // inside over outside
  RoughnessParams roughness;
  ColorParam reflect_tint{Rgb(1)}, transmit_tint{Rgb(1)};
};
struct ThinDielectricParams {
  FloatParam eta{1.5f};
  ColorParam reflect_tint{Rgb(1)}, transmit_tint{Rgb(1)};
};
struct CoatedDiffuseParams {
  ColorParam albedo{Rgb(0.5f)};
  FloatParam eta{1.5f};
  RoughnessParams roughness;
};
struct MixParams {
  FloatParam amount;  // 0 = a, 1 = b; fractional values pick b with that probability
  MaterialRef a, b;
};
// A Bump perturbs the shading normal by a height texture, or (normal_mapped) by a tangent-space normal map
// whose x and y are multiplied by `scale` (glTF's normalTexture.scale).
struct BumpParams {
  FloatParam height;  // displacement along the shading normal, in world units (times scale)
  float scale = 1;
  MaterialRef inner;
  bool normal_mapped = false;
  ColorParam normal_map{Rgb(0.5f, 0.5f, 1.0f)};  // rgb = (n_tangent + 1) / 2; tangent along dp/du, bitangent dp/dv
};

// One array per material type (structure of arrays across types).
struct MaterialTables {
  std::vector<LambertParams> lambert;
  std::vector<OrenNayarParams> oren_nayar;
  std::vector<MirrorParams> mirror;
  std::vector<ConductorParams> conductor;
  std::vector<DielectricParams> dielectric;
  std::vector<ThinDielectricParams> thin_dielectric;
  std::vector<CoatedDiffuseParams> coated_diffuse;
  std::vector<MixParams> mix;
  std::vector<BumpParams> bump;
};

}  // namespace torte
