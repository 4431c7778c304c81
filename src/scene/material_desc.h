// Builder-side materials: what torte.material.* creates from Lua. Parameters are constants or texture graphs
// (FloatInput/ColorInput); Mix and Bump reference other materials, so materials form an immutable DAG shared by
// pointer. flatten_material() turns one into the scene's per-type tables (material/material.h), storing each
// distinct material and texture once.
#pragma once
#include <map>
#include <memory>

#include "material/material.h"
#include "texture/texture.h"

namespace torte {

struct RoughnessInput {
  FloatInput u, v;  // see RoughnessParams
  MicrofacetDistribution::Kind distribution = MicrofacetDistribution::Kind::GGX;
  bool remap = true;
};

// Which fields a type reads:
//   Lambert: color             OrenNayar: color, sigma        Mirror: color
//   Conductor: eta_rgb, k, roughness                          CoatedDiffuse: color, eta, roughness
//   Dielectric: eta, roughness, color (reflection tint), transmit_color
//   ThinDielectric: eta, color, transmit_color
//   Mix: a, b, amount           Bump: a (inner material), height, bump_scale
struct MaterialDesc {
  MaterialType type = MaterialType::Lambert;
  ColorInput color{Rgb(0.5f), nullptr};
  ColorInput transmit_color{Rgb(1), nullptr};
  ColorInput eta_rgb, k;
  FloatInput eta{1.5f, nullptr};
  FloatInput sigma;
  RoughnessInput roughness;
  std::shared_ptr<const MaterialDesc> a, b;
  FloatInput amount{0.5f, nullptr};
  FloatInput height;
  ColorInput normal_map;        // a Bump by a normal map (make_normal_map) instead of `height`
  // A cut-out (torte.material.mask): the surface is absent where alpha < alpha_cutoff (Scene::alpha_masks).
  bool alpha_masked = false;
  bool alpha_stochastic = false;
  FloatInput alpha{1.0f, nullptr};
  float alpha_cutoff = 0.5f;
  bool normal_mapped = false;
  float bump_scale = 1;
  int nesting = 0;  // Mix/Bump levels above the deepest leaf below (0 for a shaded material); set by make_mix/make_bump
};

/// A Mix of `a` and `b` (b with probability `amount`) and a Bump of `inner`. Throw torte::Error when the result
/// would nest Mix/Bump materials more than kMaxMaterialNesting levels deep (material/material.h), which keeps
/// flattening, resolution at render time and the destruction of the shared chain bounded.
std::shared_ptr<MaterialDesc> make_mix(std::shared_ptr<const MaterialDesc> a, std::shared_ptr<const MaterialDesc> b,
                                       FloatInput amount);
std::shared_ptr<MaterialDesc> make_bump(std::shared_ptr<const MaterialDesc> inner, FloatInput height, float scale);
/// A Bump of `inner` by a tangent-space normal map (OpenGL convention: +y along dp/dv), x and y times `scale`.
std::shared_ptr<MaterialDesc> make_normal_map(std::shared_ptr<const MaterialDesc> inner, ColorInput map, float scale);

/// Checks a scene's flattened tables: every Mix/Bump reference names an existing row, and Mix/Bump rows nest at
/// most kMaxMaterialNesting levels without cycles, so resolve_material (render/material_resolve.h) always ends on
/// a shaded material. Throws torte::Error otherwise.
void validate_material_tables(const MaterialTables& tables);

// Flattens materials into MaterialTables, deduplicating by pointer; textures go through `textures`.
class MaterialFlattener {
 public:
  MaterialFlattener(MaterialTables& tables, TextureTableBuilder& textures) : tables_(tables), textures_(textures) {}
  /// Throws torte::Error for a material nesting more than kMaxMaterialNesting Mix/Bump levels.
  MaterialRef add(const MaterialDesc& desc) { return add(desc, 0); }

 private:
  MaterialRef add(const MaterialDesc& desc, int level);
  RoughnessParams roughness(const RoughnessInput& r);
  MaterialTables& tables_;
  TextureTableBuilder& textures_;
  std::map<const MaterialDesc*, MaterialRef> refs_;
};

}  // namespace torte
