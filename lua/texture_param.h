// Texture-valued keyword arguments, for the bindings of torte.material.* (and anything else that takes a
// number/colour or a torte.texture). Implemented in lua/bind_texture.cc.
#pragma once
#include "binding.h"
#include "texture/texture.h"
#include "texture/texture_param.h"

namespace torte::lua {

// A torte.texture is a userdata holding std::shared_ptr<const TextureDesc> (push_object / to_object with
// T = const TextureDesc).
template <>
struct LuaName<const TextureDesc> {
  static constexpr const char* value = "torte.texture";
};

// kw[key]: absent -> default_value; a number; or a scalar (Float-valued) torte.texture. Anything else fails
// with the function, key and what was given ("torte.material.x: 'roughness' expects a scalar texture, got a
// colour texture"); the script location is added by the binding guard.
FloatInput float_input(KwArgs& kw, const char* key, float default_value);
// kw[key]: absent -> default_value; a number (grey) or {r, g, b} (finite, non-negative, as KwArgs::rgb); or a
// colour or scalar torte.texture (a scalar one is broadcast to grey).
ColorInput color_input(KwArgs& kw, const char* key, Rgb default_value);
// Whether the value at `index` is a torte.texture.
bool is_texture(lua_State* L, int index);

}  // namespace torte::lua
