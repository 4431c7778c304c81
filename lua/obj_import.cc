#include "obj_import.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/text.h"
#include "file_access.h"
#include "origin.h"
#include "texture/image_texture_oiio.h"
#include "texture_param.h"

namespace torte::lua {

namespace {

void warn(const std::string& message) { std::fprintf(stderr, "torte: warning: %s\n", message.c_str()); }

// An image texture of `path`, or null (with a warning) when it cannot be opened: a model whose texture is missing
// still renders, in its constant colour.
TexturePtr image_or_warn(lua_State* L, const std::string& path, const std::string& function, bool scalar) {
  try {
    check_read(L, path, function.c_str());
    ImageTextureOptions o;
    if (scalar) o.color_space = ImageTextureOptions::ColorSpace::Linear;  // heights are data, not colour
    auto source = open_image_texture(path, o);
    return scalar ? texture::image_scalar(std::move(source)) : texture::image(std::move(source));
  } catch (const Error& e) {
    warn(function + ": " + e.what() + " (the map is ignored)");
    return nullptr;
  }
}

Rgb clamp01(Rgb c) {
  return {std::clamp(c.r, 0.0f, 1.0f), std::clamp(c.g, 0.0f, 1.0f), std::clamp(c.b, 0.0f, 1.0f)};
}

}  // namespace

bool is_obj_path(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".obj";
}

ObjData load_obj_file(const std::string& path, const std::string& function) {
  ObjData data;
  try {
    data = read_obj(path);
  } catch (const Error& e) {
    throw Error(function + ": " + e.what());
  }
  for (const std::string& w : data.warnings) warn(w);
  return data;
}

std::shared_ptr<MaterialDesc> material_from_obj(lua_State* L, const ObjMaterial& m, const std::string& function) {
  auto surface = std::make_shared<MaterialDesc>();
  surface->color = {clamp01(m.kd), nullptr};
  const std::string where = function + ": material " + quote_text(m.name, 60);
  if (!m.map_kd.empty()) surface->color.texture = image_or_warn(L, m.map_kd, where, false);
  if (m.ks.max_component() > 0) {
    // A Phong lobe of exponent Ns has about the width of a microfacet alpha = sqrt(2 / (Ns + 2)) (Walter et al.
    // 2007); torte's roughness is remapped as alpha = roughness^2.
    surface->type = MaterialType::CoatedDiffuse;
    surface->eta = {std::max(m.ni, 1.001f), nullptr};
    const float alpha = std::sqrt(2.0f / (std::max(m.ns, 0.0f) + 2.0f));
    surface->roughness.u = surface->roughness.v = {std::sqrt(alpha), nullptr};
  }
  std::shared_ptr<MaterialDesc> out = surface;
  if (m.d < 1) {  // partly transparent: a stochastic mix with a thin sheet of glass passing what d lets through
    auto glass = std::make_shared<MaterialDesc>();
    glass->type = MaterialType::ThinDielectric;
    glass->eta = {std::max(m.ni, 1.001f), nullptr};
    glass->color = {Rgb(1), nullptr};
    glass->transmit_color = {Rgb(1), nullptr};
    out = make_mix(out, glass, {1 - m.d, nullptr});
  }
  if (!m.map_bump.empty())
    if (TexturePtr height = image_or_warn(L, m.map_bump, where, true))
      out = make_bump(out, {0, height}, m.bump_scale);
  return out;
}

void push_obj_shapes(lua_State* L, const ObjData& data, const ShapeDesc& base, bool use_emission,
                     const std::string& function) {
  std::vector<ObjPart> parts = split_by_material(data);
  lua_createtable(L, int(parts.size()), 0);
  int i = 0;
  for (ObjPart& part : parts) {
    ShapeDesc s = base;
    s.kind = ShapeDesc::Kind::Mesh;
    if (part.material >= 0) {
      const ObjMaterial& m = data.materials[size_t(part.material)];
      s.material = material_from_obj(L, m, function);
      if (use_emission && m.ke.max_component() > 0) s.emission = Rgb(std::min(m.ke.r, kMaxEmission),
                                                                     std::min(m.ke.g, kMaxEmission),
                                                                     std::min(m.ke.b, kMaxEmission));
    }
    part.mesh.validate(function);
    s.mesh = std::make_shared<const TriangleMesh>(std::move(part.mesh));
    push_object(L, std::make_shared<ShapeDesc>(std::move(s)));
    lua_rawseti(L, -2, ++i);
  }
}

void push_obj_materials(lua_State* L, const ObjData& data, const std::string& function) {
  std::vector<ObjPart> parts = split_by_material(data);
  lua_createtable(L, int(data.materials.size()), int(data.materials.size()));
  int i = 0;
  for (size_t k = 0; k < data.materials.size(); ++k) {
    const ObjMaterial& m = data.materials[k];
    lua_createtable(L, 0, 4);
    lua_pushlstring(L, m.name.data(), m.name.size());
    lua_setfield(L, -2, "name");
    push_object(L, material_from_obj(L, m, function));
    lua_setfield(L, -2, "material");
    lua_createtable(L, 3, 0);
    const float ke[3] = {m.ke.r, m.ke.g, m.ke.b};
    for (int c = 0; c < 3; ++c) {
      lua_pushnumber(L, ke[c]);
      lua_rawseti(L, -2, c + 1);
    }
    lua_setfield(L, -2, "emission");
    for (ObjPart& part : parts)
      if (part.material == int32_t(k)) {
        push_object(L, std::make_shared<TriangleMesh>(std::move(part.mesh)));
        lua_setfield(L, -2, "mesh");
      }
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, m.name.c_str());
    lua_rawseti(L, -2, ++i);
  }
}

}  // namespace torte::lua
