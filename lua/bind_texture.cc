// torte.texture.*: composable textures (see src/texture/texture.h for the model and docs/textures.md).
//
//   local T = torte.texture
//   local marble = T.spline{colors = {{0.9, 0.9, 0.85}, {0.3, 0.3, 0.35}}} .. T.turbulence{octaves = 5}
//                  .. T.xyz{transform = torte.scale(0.2, 0.2, 0.2)}
//   local floor = T.checker{a = 0.8, b = 0.1} .. T.uv{scale = 8}
//   local wood  = 0.5 * T.image{file = "wood.png"} + 0.1       -- numbers and {r, g, b} become constants
//   print(floor:eval{uv = {0.1, 0.1}}[1], marble.type, marble.input)
//
// Operators on torte.texture values (numbers and {r, g, b} tables are promoted to constant textures):
//   a + b, a - b     add (a - b = a + (-1) b)       a * b     multiply (texture * number = scale)
//   a / number       scale by 1 / number            f .. g    compose: f o g, g's output feeds f's input
// Types are checked when the texture is built: a Vec3-input noise composed with a uv mapping, or a 2D-vector
// texture used as a colour, fails with the function and key at the script's line.
#include <cmath>

#include "file_access.h"
#include "runtime.h"
#include "texture/image_texture_oiio.h"
#include "texture_param.h"
#include "types.h"

namespace torte::lua {

namespace {

using texture::close;

const char* lua_type_name(ValueType t) {
  switch (t) {
    case ValueType::None: return "none";
    case ValueType::Float: return "float";
    case ValueType::Vec2: return "vec2";
    case ValueType::Vec3: return "vec3";
    case ValueType::Rgb: return "color";
  }
  return "?";
}

void push_texture(lua_State* L, TexturePtr t) { push_object<const TextureDesc>(L, std::move(t)); }

// The value at idx as a texture: a torte.texture, a number (scalar constant) or {r, g, b} (colour constant);
// nullptr for anything else.
TexturePtr to_texture(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  if (auto t = to_object<const TextureDesc>(L, idx)) return t;
  if (lua_type(L, idx) == LUA_TNUMBER) return texture::constant(float(lua_tonumber(L, idx)));
  if (lua_istable(L, idx) && lua_rawlen(L, idx) == 3) {
    const Vec3f v = check_vec3(L, idx, "a colour");
    return texture::constant(Rgb(v.x, v.y, v.z));
  }
  return nullptr;
}

// Runs a texture constructor; its torte::Error gets the function's name in front.
template <class F>
TexturePtr build(const std::string& fn, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(fn + ": " + e.what());
  }
}

// A keyword table at argument 1 (none given: an empty one, so T.xyz() works like T.xyz{}).
KwArgs kwargs(lua_State* L, const char* fn) {
  if (lua_isnoneornil(L, 1)) {
    lua_settop(L, 0);
    lua_newtable(L);
  }
  return KwArgs(L, 1, fn);
}

// kw[key] as a texture (number / {r,g,b} / torte.texture); `fallback` when absent (nullptr: required).
TexturePtr texture_arg(KwArgs& kw, lua_State* L, const char* key, TexturePtr fallback = nullptr) {
  kw.push(key);
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    if (!fallback) kw.fail(key, "is required (a torte.texture, a number or {r, g, b})");
    return fallback;
  }
  TexturePtr t;
  try {
    t = to_texture(L, -1);
  } catch (const Error&) {
    t = nullptr;
  }
  if (!t) {
    const std::string got = type_name(L, -1);
    lua_pop(L, 1);
    kw.fail(key, "must be a torte.texture, a number or {r, g, b}, got " + got);
  }
  lua_pop(L, 1);
  return t;
}

// {x, y} or one number for both.
Vec2f vec2_arg(KwArgs& kw, lua_State* L, const char* key, Vec2f fallback) {
  kw.push(key);
  Vec2f v = fallback;
  if (lua_type(L, -1) == LUA_TNUMBER) {
    v = Vec2f(float(lua_tonumber(L, -1)), float(lua_tonumber(L, -1)));
  } else if (lua_istable(L, -1) && lua_rawlen(L, -1) == 2) {
    for (int i = 0; i < 2; ++i) {
      lua_rawgeti(L, -1, i + 1);
      int ok = 0;
      (i == 0 ? v.x : v.y) = float(lua_tonumberx(L, -1, &ok));
      lua_pop(L, 1);
      if (!ok) {
        lua_pop(L, 1);
        kw.fail(key, "must hold 2 numbers {x, y}");
      }
    }
  } else if (!lua_isnil(L, -1)) {
    const std::string got = type_name(L, -1);
    lua_pop(L, 1);
    kw.fail(key, "must be a number or {x, y}, got " + got);
  }
  lua_pop(L, 1);
  if (!std::isfinite(v.x) || !std::isfinite(v.y)) kw.fail(key, "must be finite");
  return v;
}

int l_constant(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.constant");
  TexturePtr t = texture_arg(kw, L, "value");
  kw.finish();
  if (t->kind != TextureKind::Constant) kw.fail("value", "must be a number or {r, g, b}");
  push_texture(L, std::move(t));
  return 1;
}

int l_uv(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.uv");
  const Vec2f s = vec2_arg(kw, L, "scale", {1, 1}), o = vec2_arg(kw, L, "offset", {0, 0});
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::uv(s, o); }));
  return 1;
}

template <TexturePtr (*Make)(const Transform&)>
int l_transformed(lua_State* L, const char* fn) {
  KwArgs kw = kwargs(L, fn);
  const Transform t = kw.transform("transform");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return Make(t); }));
  return 1;
}
int l_spherical(lua_State* L) { return l_transformed<texture::spherical>(L, "torte.texture.spherical"); }
int l_cylindrical(lua_State* L) { return l_transformed<texture::cylindrical>(L, "torte.texture.cylindrical"); }
int l_xyz(lua_State* L) { return l_transformed<texture::xyz>(L, "torte.texture.xyz"); }

int l_planar(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.planar");
  const Vec3f s = kw.vec3("s", Vec3f(1, 0, 0)), t = kw.vec3("t", Vec3f(0, 1, 0));
  const Vec2f o = vec2_arg(kw, L, "offset", {0, 0});
  const Transform tr = kw.transform("transform");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::planar(s, t, o, tr); }));
  return 1;
}

int checker(lua_State* L, const char* fn, int dims) {
  KwArgs kw = kwargs(L, fn);
  TexturePtr a = texture_arg(kw, L, "a", texture::constant(1.0f));
  TexturePtr b = texture_arg(kw, L, "b", texture::constant(0.0f));
  const float scale = float(kw.number("scale", 1));
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::checker(a, b, dims, scale); }));
  return 1;
}
int l_checker(lua_State* L) { return checker(L, "torte.texture.checker", 2); }
int l_checker3d(lua_State* L) { return checker(L, "torte.texture.checker3d", 3); }

int noise(lua_State* L, const char* fn, NoiseBasis basis, NoiseFractal fractal) {
  KwArgs kw = kwargs(L, fn);
  NoiseParams p;
  p.basis = basis;
  p.fractal = fractal;
  p.dims = kw.integer("dims", 3);
  const double seed = kw.number("seed", 0);
  if (seed < 0 || seed != std::floor(seed) || seed > 4294967295.0) kw.fail("seed", "must be an integer in [0, 2^32)");
  p.seed = uint32_t(seed);
  if (fractal != NoiseFractal::None) {
    const std::string b = kw.string("basis", "perlin");
    if (b == "perlin") p.basis = NoiseBasis::Perlin;
    else if (b == "value") p.basis = NoiseBasis::Value;
    else kw.fail("basis", "must be \"perlin\" or \"value\", got \"" + b + "\"");
    p.octaves = kw.integer("octaves", 6);
    p.lacunarity = float(kw.number("lacunarity", 2));
    p.gain = float(kw.number("gain", 0.5));
  }
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::noise(p); }));
  return 1;
}
int l_value_noise(lua_State* L) {
  return noise(L, "torte.texture.value_noise", NoiseBasis::Value, NoiseFractal::None);
}
int l_perlin(lua_State* L) { return noise(L, "torte.texture.perlin", NoiseBasis::Perlin, NoiseFractal::None); }
int l_fbm(lua_State* L) { return noise(L, "torte.texture.fbm", NoiseBasis::Perlin, NoiseFractal::Fbm); }
int l_turbulence(lua_State* L) {
  return noise(L, "torte.texture.turbulence", NoiseBasis::Perlin, NoiseFractal::Turbulence);
}

int l_image(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.image");
  const std::string file = resolve_script_path(L, kw.string("file"));
  check_read(L, file, "torte.texture.image");
  ImageTextureOptions o;
  const std::string wrap = kw.string("wrap", "periodic");
  if (wrap == "periodic" || wrap == "repeat") o.wrap = ImageTextureOptions::Wrap::Periodic;
  else if (wrap == "clamp") o.wrap = ImageTextureOptions::Wrap::Clamp;
  else if (wrap == "black") o.wrap = ImageTextureOptions::Wrap::Black;
  else if (wrap == "mirror") o.wrap = ImageTextureOptions::Wrap::Mirror;
  else kw.fail("wrap", "must be \"periodic\", \"clamp\", \"black\" or \"mirror\", got \"" + wrap + "\"");
  const std::string filter = kw.string("filter", "trilinear");
  if (filter == "trilinear") o.filter = ImageTextureOptions::Filter::Trilinear;
  else if (filter == "bilinear") o.filter = ImageTextureOptions::Filter::Bilinear;
  else if (filter == "closest" || filter == "nearest") o.filter = ImageTextureOptions::Filter::Closest;
  else kw.fail("filter", "must be \"trilinear\", \"bilinear\" or \"closest\", got \"" + filter + "\"");
  const std::string cs = kw.string("color_space", "auto");
  if (cs == "auto") o.color_space = ImageTextureOptions::ColorSpace::Auto;
  else if (cs == "srgb" || cs == "sRGB") o.color_space = ImageTextureOptions::ColorSpace::Srgb;
  else if (cs == "linear") o.color_space = ImageTextureOptions::ColorSpace::Linear;
  else kw.fail("color_space", "must be \"auto\", \"srgb\" or \"linear\", got \"" + cs + "\"");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::image(open_image_texture(file, o)); }));
  return 1;
}

int l_grayscale(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.grayscale");
  kw.finish();
  push_texture(L, texture::grayscale());
  return 1;
}

int l_spline(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.spline");
  std::vector<Rgb> colors;
  kw.push("colors");
  if (!lua_istable(L, -1)) {
    const std::string got = type_name(L, -1);
    lua_pop(L, 1);
    kw.fail("colors", "must be an array of colours {{r, g, b}, ...} or numbers, got " + got);
  }
  const lua_Integer n = lua_Integer(lua_rawlen(L, -1));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    if (lua_type(L, -1) == LUA_TNUMBER) {
      colors.push_back(Rgb(float(lua_tonumber(L, -1))));
    } else {
      Vec3f v;
      try {
        v = check_vec3(L, -1, kw.function() + ": 'colors' entry " + std::to_string(i));
      } catch (...) {
        lua_pop(L, 2);
        throw;
      }
      colors.push_back(Rgb(v.x, v.y, v.z));
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::vector<float> positions;
  if (kw.has("positions"))
    for (double p : kw.numbers("positions")) positions.push_back(float(p));
  else
    kw.push("positions"), lua_pop(L, 1);  // mark as accepted
  const std::string interp = kw.string("interpolation", "catmull-rom");
  if (interp != "catmull-rom" && interp != "linear")
    kw.fail("interpolation", "must be \"catmull-rom\" or \"linear\", got \"" + interp + "\"");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::spline(colors, positions, interp == "linear"); }));
  return 1;
}

int l_add(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.add");
  TexturePtr a = texture_arg(kw, L, "a"), b = texture_arg(kw, L, "b");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::add(a, b); }));
  return 1;
}

int l_multiply(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.multiply");
  TexturePtr a = texture_arg(kw, L, "a"), b = texture_arg(kw, L, "b");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::multiply(a, b); }));
  return 1;
}

int l_scale(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.scale");
  TexturePtr a = texture_arg(kw, L, "texture");
  const float factor = float(kw.number("factor"));
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::scale(a, factor); }));
  return 1;
}

int lerp_impl(lua_State* L, const char* fn) {
  KwArgs kw = kwargs(L, fn);
  TexturePtr t = texture_arg(kw, L, "t"), a = texture_arg(kw, L, "a"), b = texture_arg(kw, L, "b");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::lerp(t, a, b); }));
  return 1;
}
int l_lerp(lua_State* L) { return lerp_impl(L, "torte.texture.lerp"); }
int l_mix(lua_State* L) { return lerp_impl(L, "torte.texture.mix"); }

int l_compose(lua_State* L) {
  KwArgs kw = kwargs(L, "torte.texture.compose");
  TexturePtr outer = texture_arg(kw, L, "outer"), inner = texture_arg(kw, L, "inner");
  kw.finish();
  push_texture(L, build(kw.function(), [&] { return texture::compose(outer, inner); }));
  return 1;
}

// ---- operators ---------------------------------------------------------------------------------------------

TexturePtr operand(lua_State* L, int idx, const char* op) {
  TexturePtr t;
  try {
    t = to_texture(L, idx);
  } catch (const Error&) {
    t = nullptr;
  }
  if (!t)
    throw Error(std::string("torte.texture operator ") + op +
                ": operands must be torte.texture values, numbers or {r, g, b} colours, got " + type_name(L, idx));
  return t;
}

bool is_number(lua_State* L, int idx) { return lua_type(L, idx) == LUA_TNUMBER; }

int op_add(lua_State* L) {
  TexturePtr a = operand(L, 1, "+"), b = operand(L, 2, "+");
  push_texture(L, build("torte.texture operator +", [&] { return texture::add(a, b); }));
  return 1;
}

int op_sub(lua_State* L) {
  TexturePtr a = operand(L, 1, "-"), b = operand(L, 2, "-");
  push_texture(L, build("torte.texture operator -", [&] { return texture::add(a, texture::scale(b, -1)); }));
  return 1;
}

int op_unm(lua_State* L) {
  TexturePtr a = operand(L, 1, "-");
  push_texture(L, build("torte.texture operator -", [&] { return texture::scale(a, -1); }));
  return 1;
}

int op_mul(lua_State* L) {
  const char* fn = "torte.texture operator *";
  if (is_number(L, 1) || is_number(L, 2)) {  // texture * number or number * texture: a scale node
    const int num = is_number(L, 1) ? 1 : 2;
    TexturePtr t = operand(L, 3 - num, "*");
    const float f = float(lua_tonumber(L, num));
    push_texture(L, build(fn, [&] { return texture::scale(t, f); }));
    return 1;
  }
  TexturePtr a = operand(L, 1, "*"), b = operand(L, 2, "*");
  push_texture(L, build(fn, [&] { return texture::multiply(a, b); }));
  return 1;
}

int op_div(lua_State* L) {
  if (!is_number(L, 2))
    throw Error("torte.texture operator /: only division by a number is supported, got " + type_name(L, 2));
  TexturePtr t = operand(L, 1, "/");
  const double d = lua_tonumber(L, 2);
  if (d == 0) throw Error("torte.texture operator /: division by zero");
  push_texture(L, build("torte.texture operator /", [&] { return texture::scale(t, float(1 / d)); }));
  return 1;
}

int op_concat(lua_State* L) {
  TexturePtr f = operand(L, 1, ".."), g = operand(L, 2, "..");
  push_texture(L, build("torte.texture operator .. (compose)", [&] { return texture::compose(f, g); }));
  return 1;
}

TexturePtr self(lua_State* L, const char* what) {
  auto t = to_object<const TextureDesc>(L, 1);
  if (!t) throw Error(std::string(what) + " expects a torte.texture, got " + type_name(L, 1));
  return t;
}

int op_tostring(lua_State* L) {
  TexturePtr t = self(L, "tostring");
  std::string s = std::string("torte.texture (") + texture_kind_name(t->kind) + ": " +
                  lua_type_name(t->input) + " -> " + lua_type_name(t->output);
  if (t->image) s += ", " + t->image->description();
  s += ")";
  lua_pushstring(L, s.c_str());
  return 1;
}

// t:eval{uv = {u, v}, p = {x, y, z}, n = {x, y, z}, dpdu = ..., dpdv = ..., footprint = 0, input = ...}.
// Without `input` the texture is closed (a pattern reads uv or p); with it, `input` (a number, {x, y} or
// {x, y, z} matching t.input) is fed to the texture directly. Returns a number for scalar textures and a table
// ({r, g, b}, {x, y} or {x, y, z}) otherwise.
int l_eval(lua_State* L) {
  TexturePtr t = self(L, "eval");
  if (lua_isnoneornil(L, 2)) {
    lua_settop(L, 1);
    lua_newtable(L);
  }
  KwArgs kw(L, 2, "torte.texture:eval");
  TextureContext ctx;
  const Vec2f uv = vec2_arg(kw, L, "uv", {0, 0});
  ctx.uv = uv;
  ctx.p = kw.vec3("p", Vec3f(0, 0, 0));
  ctx.n = kw.vec3("n", Vec3f(0, 0, 1));
  ctx.dpdu = kw.vec3("dpdu", Vec3f(0, 0, 0));
  ctx.dpdv = kw.vec3("dpdv", Vec3f(0, 0, 0));
  ctx.footprint = float(kw.number("footprint", 0));
  TexValue in;
  const bool has_input = kw.has("input");
  if (has_input) {
    if (t->input == ValueType::None) kw.fail("input", "is not taken by this texture (it reads only uv, p, n)");
    if (t->input == ValueType::Float) {
      in.x = in.y = in.z = float(kw.number("input"));
    } else if (t->input == ValueType::Vec2) {
      const Vec2f v = vec2_arg(kw, L, "input", {0, 0});
      in.x = v.x, in.y = v.y;
    } else {
      const Vec3f v = kw.vec3("input");
      in.x = v.x, in.y = v.y, in.z = v.z;
    }
  } else {
    kw.push("input");
    lua_pop(L, 1);
  }
  kw.finish();
  TextureTableBuilder builder;
  const int32_t root = builder.add_node(has_input ? t : build(kw.function(), [&] { return close(t); }));
  const TextureTable table = builder.finish();
  const TexValue v = table.eval_node(root, ctx, in);
  switch (t->output) {
    case ValueType::Float:
      lua_pushnumber(L, v.x);
      return 1;
    case ValueType::Vec2:
      lua_createtable(L, 2, 0);
      lua_pushnumber(L, v.x), lua_rawseti(L, -2, 1);
      lua_pushnumber(L, v.y), lua_rawseti(L, -2, 2);
      return 1;
    default:
      lua_createtable(L, 3, 0);
      lua_pushnumber(L, v.x), lua_rawseti(L, -2, 1);
      lua_pushnumber(L, v.y), lua_rawseti(L, -2, 2);
      lua_pushnumber(L, v.z), lua_rawseti(L, -2, 3);
      return 1;
  }
}

int op_index(lua_State* L) {
  TexturePtr t = self(L, "texture field");
  const std::string key = luaL_checkstring(L, 2);
  if (key == "type") lua_pushstring(L, lua_type_name(t->output));
  else if (key == "input") lua_pushstring(L, lua_type_name(t->input));
  else if (key == "kind") lua_pushstring(L, texture_kind_name(t->kind));
  else if (push_method(L, 1, key)) {
  } else
    throw Error("torte.texture has no field '" + key + "' (fields: type, input, kind; methods: eval)");
  return 1;
}

// The accepted input of a texture used as a material parameter: closable, with an allowed output.
void check_param_texture(KwArgs& kw, const char* key, const TexturePtr& t, bool colour) {
  if (t->output == ValueType::Rgb && !colour) kw.fail(key, "expects a scalar texture, got a colour texture");
  if (t->output != ValueType::Float && t->output != ValueType::Rgb)
    kw.fail(key, std::string("expects a ") + (colour ? "colour or scalar" : "scalar") + " texture, got a " +
                     value_type_name(t->output) + " texture");
  if (t->input == ValueType::Float)
    kw.fail(key, std::string("got a ") + texture_kind_name(t->kind) +
                     " texture that takes a scalar input; compose it with a scalar texture first (map .. noise)");
}

}  // namespace

bool is_texture(lua_State* L, int index) { return to_object<const TextureDesc>(L, index) != nullptr; }

namespace {
// kw[key] as a parameter texture, or nullptr when absent or not a texture (a number or table is left to the
// caller).
TexturePtr param_texture(KwArgs& kw, const char* key, bool colour) {
  lua_State* L = kw.state();
  kw.push(key);
  TexturePtr t = to_object<const TextureDesc>(L, -1);
  const int type = lua_type(L, -1);
  const std::string got = type_name(L, -1);
  lua_pop(L, 1);
  if (t) {
    check_param_texture(kw, key, t, colour);
    return t;
  }
  if (type == LUA_TNIL || type == LUA_TNUMBER || (colour && type == LUA_TTABLE)) return nullptr;
  kw.fail(key, std::string("expects ") + (colour ? "a colour {r, g, b}, a number or a torte.texture"
                                                 : "a number or a scalar torte.texture") +
                   ", got " + got);
}
}  // namespace

FloatInput float_input(KwArgs& kw, const char* key, float default_value) {
  if (TexturePtr t = param_texture(kw, key, false)) return {0, std::move(t)};
  const float v = float(kw.number(key, default_value));
  if (!std::isfinite(v)) kw.fail(key, "must be finite (it overflows float)");
  return {v, nullptr};
}

ColorInput color_input(KwArgs& kw, const char* key, Rgb default_value) {
  if (TexturePtr t = param_texture(kw, key, true)) return {Rgb(), std::move(t)};
  return {kw.rgb(key, default_value), nullptr};
}

void open_textures(lua_State* L, int torte_index) {
  torte_index = lua_absindex(L, torte_index);
  // The metatable gets its fields once; push_object creates it on first use, so make a texture now.
  push_texture(L, texture::constant(0.0f));
  lua_getmetatable(L, -1);
  const luaL_Reg meta[] = {{"__index", guarded<op_index>},   {"__tostring", guarded<op_tostring>},
                           {"__add", guarded<op_add>},       {"__sub", guarded<op_sub>},
                           {"__unm", guarded<op_unm>},       {"__mul", guarded<op_mul>},
                           {"__div", guarded<op_div>},       {"__concat", guarded<op_concat>},
                           {nullptr, nullptr}};
  set_functions(L, meta);
  const luaL_Reg methods[] = {{"eval", guarded<l_eval>}, {nullptr, nullptr}};
  set_methods(L, methods);
  lua_pop(L, 2);

  const luaL_Reg fns[] = {{"constant", guarded<l_constant>},
                          {"uv", guarded<l_uv>},
                          {"spherical", guarded<l_spherical>},
                          {"cylindrical", guarded<l_cylindrical>},
                          {"planar", guarded<l_planar>},
                          {"xyz", guarded<l_xyz>},
                          {"checker", guarded<l_checker>},
                          {"checker3d", guarded<l_checker3d>},
                          {"value_noise", guarded<l_value_noise>},
                          {"perlin", guarded<l_perlin>},
                          {"noise", guarded<l_perlin>},
                          {"fbm", guarded<l_fbm>},
                          {"turbulence", guarded<l_turbulence>},
                          {"image", guarded<l_image>},
                          {"grayscale", guarded<l_grayscale>},
                          {"spline", guarded<l_spline>},
                          {"add", guarded<l_add>},
                          {"multiply", guarded<l_multiply>},
                          {"scale", guarded<l_scale>},
                          {"lerp", guarded<l_lerp>},
                          {"mix", guarded<l_mix>},
                          {"compose", guarded<l_compose>},
                          {nullptr, nullptr}};
  push_subtable(L, torte_index, "texture");
  set_functions(L, fns);
  lua_pop(L, 1);
}

}  // namespace torte::lua
