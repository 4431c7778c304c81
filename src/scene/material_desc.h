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
  float bump_scale = 1;
};

// Flattens materials into MaterialTables, deduplicating by pointer; textures go through `textures`.
class MaterialFlattener {
 public:
  MaterialFlattener(MaterialTables& tables, TextureTableBuilder& textures) : tables_(tables), textures_(textures) {}
  MaterialRef add(const MaterialDesc& desc);

 private:
  RoughnessParams roughness(const RoughnessInput& r);
  MaterialTables& tables_;
  TextureTableBuilder& textures_;
  std::map<const MaterialDesc*, MaterialRef> refs_;
};

}  // namespace torte
