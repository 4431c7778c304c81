// torte.material.*: matte, plastic, metal, mirror, glass, rough_glass, mix, bump. Every parameter may be a
// constant or a texture (lua/texture_param.h); constants are range-checked here, with errors that name the key,
// the file and the line. Roughness is in [0, 1] and remapped to the microfacet alpha = roughness^2 unless
// remap_roughness=false.
#include <cmath>

#include "material/metals.h"
#include "texture_param.h"
#include "types.h"

namespace torte::lua {

namespace {

// make_mix/make_bump, their nesting error prefixed by the function's name.
template <class Make>
std::shared_ptr<MaterialDesc> nested(const KwArgs& kw, Make&& make) {
  try {
    return make();
  } catch (const Error& e) {
    throw Error(kw.function() + ": " + e.what());
  }
}

std::shared_ptr<MaterialDesc> new_material(MaterialType type) {
  auto m = std::make_shared<MaterialDesc>();
  m->type = type;
  return m;
}

// A colour that is a reflectance: constants must lie in [0, 1] (energy conservation).
ColorInput reflectance(KwArgs& kw, const char* key, Rgb fallback) {
  ColorInput c = color_input(kw, key, fallback);
  if (!c.texture && !(c.value.r >= 0 && c.value.g >= 0 && c.value.b >= 0 && c.value.max_component() <= 1))
    kw.fail(key, "must be in [0, 1] per channel (a reflectance; energy conservation)");
  return c;
}

FloatInput positive(KwArgs& kw, const char* key, float fallback) {
  FloatInput f = float_input(kw, key, fallback);
  if (!f.texture && !(f.value > 0 && std::isfinite(f.value))) kw.fail(key, "must be positive");
  return f;
}

MicrofacetDistribution::Kind distribution(KwArgs& kw) {
  const std::string d = kw.string("distribution", "ggx");
  if (d == "ggx" || d == "GGX" || d == "trowbridge-reitz") return MicrofacetDistribution::Kind::GGX;
  if (d == "beckmann") return MicrofacetDistribution::Kind::Beckmann;
  kw.fail("distribution", "must be \"ggx\" or \"beckmann\", got \"" + d + "\"");
}

// roughness (isotropic) or roughness_u/roughness_v (anisotropic), distribution, remap_roughness.
RoughnessInput roughness(KwArgs& kw, float fallback) {
  RoughnessInput r;
  r.remap = kw.boolean("remap_roughness", true);
  // Remapped roughness lives in [0, 1]; a raw alpha may exceed 1 a little (very rough), not beyond 2.
  auto checked = [&](const char* key, FloatInput f) {
    if (!f.texture && !(f.value >= 0 && f.value <= (r.remap ? 1.0f : 2.0f)))
      kw.fail(key, r.remap ? "must be in [0, 1]" : "must be in [0, 2] (an alpha, remap_roughness=false)");
    return f;
  };
  const bool aniso = kw.has("roughness_u") || kw.has("roughness_v");
  if (aniso && kw.has("roughness")) kw.fail("roughness", "cannot be combined with roughness_u/roughness_v");
  if (aniso) {
    r.u = checked("roughness_u", float_input(kw, "roughness_u", fallback));
    r.v = checked("roughness_v", float_input(kw, "roughness_v", fallback));
  } else {
    r.u = r.v = checked("roughness", float_input(kw, "roughness", fallback));
  }
  r.distribution = distribution(kw);
  return r;
}

int l_matte(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.matte");
  auto m = new_material(MaterialType::Lambert);
  m->color = reflectance(kw, "color", Rgb(0.5f));
  m->sigma = float_input(kw, "sigma", 0);
  kw.finish();
  if (!m->sigma.texture && !(m->sigma.value >= 0 && m->sigma.value <= 90))
    kw.fail("sigma", "must be in [0, 90] degrees");
  // Oren-Nayar only when there is roughness: sigma = 0 is exactly Lambert, and cheaper.
  if (m->sigma.texture || m->sigma.value > 0) m->type = MaterialType::OrenNayar;
  push_object(L, std::move(m));
  return 1;
}

int l_plastic(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.plastic");
  auto m = new_material(MaterialType::CoatedDiffuse);
  m->color = reflectance(kw, "color", Rgb(0.5f));
  m->eta = positive(kw, "eta", 1.5f);
  m->roughness = roughness(kw, 0.1f);
  kw.finish();
  push_object(L, std::move(m));
  return 1;
}

int l_metal(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.metal");
  auto m = new_material(MaterialType::Conductor);
  Rgb eta(0.2f), k(3.9f);  // aluminium-like default when neither a preset nor eta/k is given
  if (kw.has("metal")) {
    if (kw.has("eta") || kw.has("k")) kw.fail("metal", "cannot be combined with eta/k");
    const std::string name = kw.string("metal");
    if (!metal_preset(name, &eta, &k)) {
      std::string names;
      for (std::string_view n : metal_preset_names()) names += (names.empty() ? "" : ", ") + std::string(n);
      kw.fail("metal", "unknown metal \"" + name + "\" (known: " + names + ")");
    }
  } else {
    metal_preset("aluminium", &eta, &k);
  }
  m->eta_rgb = color_input(kw, "eta", eta);
  m->k = color_input(kw, "k", k);
  m->roughness = roughness(kw, 0.1f);
  kw.finish();
  if (!m->eta_rgb.texture && !(m->eta_rgb.value.r > 0 && m->eta_rgb.value.g > 0 && m->eta_rgb.value.b > 0))
    kw.fail("eta", "must be positive per channel");
  if (!m->k.texture && !(m->k.value.r >= 0 && m->k.value.g >= 0 && m->k.value.b >= 0))
    kw.fail("k", "must be non-negative per channel");
  push_object(L, std::move(m));
  return 1;
}

int l_mirror(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.mirror");
  auto m = new_material(MaterialType::Mirror);
  m->color = reflectance(kw, "color", Rgb(1));
  kw.finish();
  push_object(L, std::move(m));
  return 1;
}

// glass and rough_glass share: eta, color (transmission tint), reflect_color.
void glass_common(KwArgs& kw, MaterialDesc& m) {
  m.eta = positive(kw, "eta", 1.5f);
  m.transmit_color = reflectance(kw, "color", Rgb(1));
  m.color = reflectance(kw, "reflect_color", Rgb(1));
}

int l_glass(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.glass");
  auto m = new_material(MaterialType::Dielectric);
  glass_common(kw, *m);
  if (kw.boolean("thin", false)) m->type = MaterialType::ThinDielectric;
  kw.finish();
  push_object(L, std::move(m));
  return 1;
}

int l_rough_glass(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.rough_glass");
  auto m = new_material(MaterialType::Dielectric);
  glass_common(kw, *m);
  m->roughness = roughness(kw, 0.1f);
  kw.finish();
  push_object(L, std::move(m));
  return 1;
}

int l_mix(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.mix");
  auto a = kw.object<MaterialDesc>("a");
  auto b = kw.object<MaterialDesc>("b");
  FloatInput amount = float_input(kw, "amount", 0.5f);
  kw.finish();
  if (!amount.texture && !(amount.value >= 0 && amount.value <= 1)) kw.fail("amount", "must be in [0, 1]");
  push_object(L, nested(kw, [&] { return make_mix(std::move(a), std::move(b), std::move(amount)); }));
  return 1;
}

// A cut-out: `material` where alpha >= cutoff, nothing elsewhere (or, stochastic, present with probability alpha).
int l_mask(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.mask");
  auto inner = kw.object<MaterialDesc>("material");
  FloatInput alpha = float_input(kw, "alpha", 1);
  const double cutoff = kw.number("cutoff", 0.5);
  const bool stochastic = kw.boolean("stochastic", false);
  kw.finish();
  if (!alpha.texture && !(alpha.value >= 0 && alpha.value <= 1)) kw.fail("alpha", "must be in [0, 1]");
  if (!(cutoff >= 0 && cutoff <= 1)) kw.fail("cutoff", "must be in [0, 1]");
  auto m = std::make_shared<MaterialDesc>(*inner);
  m->alpha_masked = true;
  m->alpha = std::move(alpha);
  m->alpha_cutoff = float(cutoff);
  m->alpha_stochastic = stochastic;
  push_object(L, std::move(m));
  return 1;
}

int l_bump(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.bump");
  auto inner = kw.object<MaterialDesc>("material");
  const bool mapped = kw.has("normal_map");
  if (mapped && kw.has("height")) kw.fail("normal_map", "and 'height' cannot both be given");
  FloatInput height = float_input(kw, "height", 0);
  ColorInput map = color_input(kw, "normal_map", Rgb(0.5f, 0.5f, 1.0f));
  const float scale = float(kw.number("scale", 1));
  kw.finish();
  if (!std::isfinite(scale)) kw.fail("scale", "must be finite");
  push_object(L, nested(kw, [&] {
    return mapped ? make_normal_map(std::move(inner), std::move(map), scale)
                  : make_bump(std::move(inner), std::move(height), scale);
  }));
  return 1;
}

}  // namespace

void open_materials(lua_State* L, int torte_index) {
  const luaL_Reg fns[] = {{"matte", guarded<l_matte>},
                          {"lambert", guarded<l_matte>},
                          {"plastic", guarded<l_plastic>},
                          {"metal", guarded<l_metal>},
                          {"mirror", guarded<l_mirror>},
                          {"glass", guarded<l_glass>},
                          {"rough_glass", guarded<l_rough_glass>},
                          {"mix", guarded<l_mix>},
                          {"bump", guarded<l_bump>},
                          {"mask", guarded<l_mask>}, {nullptr, nullptr}};
  push_subtable(L, torte_index, "material");
  set_functions(L, fns);
  lua_pop(L, 1);
}

}  // namespace torte::lua
