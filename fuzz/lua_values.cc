#include "lua_values.h"

#include <lauxlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>

#include "film/image.h"
#include "film/image_io.h"

namespace torte::fuzz {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Boundary and special numbers: float/int32/uint32/2^53 edges, denormals, the extremes.
constexpr double kSpecial[] = {kNan, kInf, -kInf, 0.0, -0.0, 0.5, 1, 2, 3, -1, 1e-300, 1e300,
                               std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::denorm_min(), 1e-45, 3.5e38, -3.5e38,
                               2147483647.0, 2147483648.0, -2147483649.0, 4294967295.0, 4294967296.0, 4294967297.0,
                               9007199254740993.0, 1e5, 65536, 16777217, 1e9, 1e18, 0.1, 255, 256, 32767, 32768,
                               -32769, 0x1p64, 1e-7};
// Values for size-like keys that must be refused on their own: negative, fractional, non-finite, past int32.
constexpr double kAbsurdCounts[] = {-1, -2147483648.0, 0.5, kNan, kInf, -kInf, 2147483648.0, 4294967296.0,
                                    4294967297.0, 1e12, 1e18, 1e300};
// Image sides that are cheap beside a small other side and must be refused beside a large one (46341^2 > 2^31;
// 1e5^2 pixels pass any memory budget).
constexpr double kHugeSides[] = {46341, 65537, 1e5, 1e9};

const char* const kSizeKeys[] = {"width", "height", "spp", "max_depth", "rr_depth", "levels", "octaves",
                                 "vpl_sets", "light_paths", "dims"};

// The pools, as one Lua chunk: objects (constructors of one object of each torte type), typed (constructors by
// the keyword that takes such an object), functions (callbacks) and odd (constructors of odd values).
const char kPoolsSource[] = R"lua(
local T = torte
local longs = T.data.nbt("\10\0\0\12\0\1a" .. string.pack(">i4i8i8", 2, 1, 2) .. "\0").a
local materials = {
  function() return T.material.matte{} end,
  function() return T.material.glass{} end,
  function() return T.material.metal{metal = "gold", roughness = 0.3} end,
  function() return T.material.mix{a = T.material.matte{}, b = T.material.mirror{}, amount = 0.5} end,
  function() return T.material.bump{material = T.material.plastic{}, height = T.texture.perlin{}} end,
}
local textures = {
  function() return T.texture.checker{} end,
  function() return T.texture.perlin{} end,
  function() return T.texture.uv{} end,
  function() return T.texture.image{file = "fx.png"} end,
  function() return T.texture.spherical{} end,
}
local scenes = {
  function() return T.scene() end,
  function() return T.group() end,
  function()
    local s = T.scene()
    s:add(T.shape.sphere{})
    s:add(T.light.point{position = {0, 3, 0}, intensity = 5})
    return s
  end,
}
local cameras = {
  function() return T.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}} end,
  function() return T.camera.orthographic{} end,
}
local transforms = {
  function() return T.identity() end,
  function() return T.translate(1, 2, 3) * T.rotate(30, {0, 1, 0}) end,
}
local meshes = {
  function() return T.mesh.load("fx.ply") end,
  function() return T.mesh.load("fx.obj") end,
}
local grids = {
  function() local g = T.voxel.grid{}; g:set(0, 0, 0, 1); g:define{id = 1, material = T.material.matte{}}; return g end,
}
local filters = {function() return T.filter.gaussian{} end}
local others = {
  function() return T.shape.sphere{} end,
  function() return T.shape.cube{} end,
  function() return T.shape.disk{emission = {1, 1, 1}} end,
  function() return T.light.point{position = {0, 2, 0}} end,
  function() return T.light.infinite{} end,
  function() return T.light.sky{} end,
  function() return T.instance{group = T.group()} end,
  function() return longs end,
  function()
    return T.render{scene = T.scene(), camera = T.camera.perspective{}, width = 2, height = 2, spp = 1}
  end,
}
local objects = {}
for _, list in ipairs{materials, textures, scenes, cameras, transforms, meshes, grids, filters, others} do
  for _, f in ipairs(list) do objects[#objects + 1] = f end
end
local typed = {
  material = materials, a = materials, b = materials,
  texture = textures, height = textures, t = textures, outer = textures, inner = textures, value = textures,
  color = textures, roughness = textures, amount = textures, input = textures,
  scene = scenes, group = scenes, shape = scenes,
  camera = cameras, transform = transforms, mesh = meshes, grid = grids, filter = filters,
}

local function recurse(f) f:frame(T.identity(), recurse) end
local functions = {
  function(...) return ... end,
  function(f) f:add(T.shape.sphere{}) end,
  function(f) f:add(T.light.point{position = {0, 1, 0}, intensity = 1}) end,
  function() error("error raised by a callback") end,
  function() error({}) end,
  function() while true do end end,
  function(f) f:frame(T.identity(), function(g) g:add(T.shape.cube{}) end) end,
  recurse,
  function() local t = {} for i = 1, 1e8 do t[i] = i end end,
  function() collectgarbage() end,
  function(f) return f end,
  function() return ("x"):rep(1 << 24) end,
  function(f) coroutine.wrap(function() f:frame(T.identity(), function() coroutine.yield() end) end)() end,
  function(f) f:add(f) end,
}

local odd = {
  function() return setmetatable({}, {__index = function() error("__index trap") end}) end,
  function() return setmetatable({1, 2, 3}, {__len = function() return math.maxinteger end}) end,
  function() local t = {}; t[1] = t; t.a = t; return t end,
  function() return {[1000000] = 1, [2] = 2} end,
  function() return io.stdout end,
  function() return coroutine.create(function() end) end,
  function() return ("x"):rep(1 << 20) end,
  function() return setmetatable({}, {__name = "torte.material"}) end,
  function() return setmetatable({}, {__gc = function() error("__gc trap") end}) end,
  function() return {0 / 0, 1 / 0, -1 / 0} end,
  function() return {1, 2, 3, 4} end,
  function() return {1, 2} end,
  function() return {{1, 2, 3}, {4, 5, 6}} end,
  function() return {x = 1, y = 2, z = 3} end,
  function() return ("\0"):rep(8192) end,
  function() local t = {} for i = 1, 4096 do t[i] = i % 7 end return t end,
  function() return math.mininteger end,
  function() return math.maxinteger end,
  function() return {1, nil, 3} end,
  function() return setmetatable({}, {__eq = function() error("__eq trap") end, __lt = function() return true end}) end,
}
return {objects = objects, typed = typed, functions = functions, odd = odd}
)lua";

const char kFixturePly[] =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n"
    "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0 -1 0 0\n1 0 0 0 0 -1 1 0\n0 1 0 0 0 -1 0 1\n0 0 1 1 1 1 1 1\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const char kFixtureObj[] =
    "mtllib fx.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
    "usemtl red\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
const char kFixtureMtl[] = "newmtl red\nKd 0.8 0.1 0.1\nmap_Kd fx.png\n";
const char* const kFixtures[] = {"fx.ply", "fx.obj", "fx.mtl", "fx.png", "fx.exr", "fx.dir"};

}  // namespace

const std::vector<std::string>& torte_keywords() {
  static const std::vector<std::string> keys = {
      "a", "amount", "angle", "aperture", "b", "basis", "c", "camera", "color", "color_space", "colors", "dims",
      "direction", "displacement", "distribution", "dpdu", "dpdv", "emission", "eta", "exposure", "extent", "eye",
      "faces", "factor", "falloff", "file", "filter", "focus_distance", "footprint", "fov", "fov_axis", "g_limit",
      "gain", "grid", "group", "height", "id", "indices", "inner", "inner_radius", "input", "integrator",
      "intensity", "interpolation", "irradiance", "k", "lacunarity", "levels", "light_paths", "look_at",
      "material", "max", "max_depth", "mesh", "metal", "min", "n", "normals", "octaves", "offset", "outer", "p",
      "points", "position", "positions", "radiance", "radius", "reflect_color", "remap_roughness", "roughness",
      "roughness_u", "roughness_v", "rr_depth", "sample_all_lights", "scale", "scene", "seed", "shape", "sigma",
      "spp", "sun", "sun_azimuth", "sun_direction", "sun_elevation", "sun_radius", "t", "texture", "thin",
      "transform", "turbidity", "two_sided", "up", "uvs", "value", "vpl_roulette", "vpl_sets", "width", "wrap",
      "z_max", "z_min", "side", "top", "bottom", "+x", "-x", "+y", "-y", "+z", "-z", "cone_angle", "falloff_start",
      "uv", "frequency", "rotation", "x", "y", "z"};
  return keys;
}

const std::vector<std::string>& torte_words() {
  static const std::vector<std::string> words = {
      "path", "direct", "igi", "gold", "silver", "copper", "aluminium", "chromium", "iridium", "tungsten", "Au",
      "ggx", "GGX", "beckmann", "trowbridge-reitz", "vertical", "horizontal", "diagonal", "auto", "srgb", "sRGB",
      "linear", "closest", "bilinear", "trilinear", "nearest", "periodic", "clamp", "black", "mirror", "repeat",
      "catmull-rom", "perlin", "value", "scalar", "float", "vec2", "vec3", "x", "y", "z", "side", "top", "bottom",
      "+x", "-y", "fx.ply", "fx.obj", "fx.mtl", "fx.png", "fx.exr", "fx.dir", "missing.png", "missing.ply", "",
      ".", "..", "r.0.0.mca", "fx.PLY", "fx", "torte.material", "torte.scene", "%s%n", "\xff\xfe"};
  return words;
}

bool sizes_work(std::string_view key) {
  for (const char* k : kSizeKeys)
    if (key == k) return true;
  return false;
}

void install_value_pools(FuzzLua& lua) {
  std::string error;
  if (!lua.run(kPoolsSource, &error)) throw std::runtime_error("fuzz value pools: " + error);
  lua_State* L = lua.state();
  for (const char* pool : {"objects", "typed", "functions", "odd"}) {
    lua_getfield(L, -1, pool);
    lua_setfield(L, LUA_REGISTRYINDEX, (std::string("torte.fuzz.") + pool).c_str());
  }
  lua_pop(L, 1);
}

std::string describe(lua_State* L, int index) {
  index = lua_absindex(L, index);
  const auto one = [L](int i) {
    size_t len = 0;
    const char* s = luaL_tolstring(L, i, &len);  // may call __tostring; callers run protected
    std::string out(s, len);
    lua_pop(L, 1);
    return out;
  };
  if (!lua_istable(L, index)) return one(index);
  std::vector<std::string> entries;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    entries.push_back(one(-2) + " = " + one(-1));
    lua_pop(L, 1);
  }
  std::sort(entries.begin(), entries.end());
  std::string out = "{";
  for (const std::string& e : entries) out += (out.size() > 1 ? ", " : "") + e;
  return out + "}";
}

size_t pool_size(lua_State* L, const char* pool) {
  lua_getfield(L, LUA_REGISTRYINDEX, pool);
  const size_t n = lua_rawlen(L, -1);
  lua_pop(L, 1);
  return n;
}

void write_fixtures() {
  write_file("fx.ply", kFixturePly);
  write_file("fx.obj", kFixtureObj);
  write_file("fx.mtl", kFixtureMtl);
  Image image(4, 4);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = Rgb(float(i % 4) / 3, float(i / 4) / 3, 0.5f);
  write_image(image, "fx.png");
  write_image(image, "fx.exr");
  std::filesystem::create_directories("fx.dir");
}

void remove_non_fixtures() {
  std::error_code ec;
  for (std::filesystem::directory_iterator it(".", ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (std::find(std::begin(kFixtures), std::end(kFixtures), name) == std::end(kFixtures)) {
      std::error_code ec2;
      std::filesystem::remove_all(it->path(), ec2);
    }
  }
}

void LuaValueMaker::push_pool_entry(const char* pool, size_t index) {
  lua_getfield(L_, LUA_REGISTRYINDEX, pool);
  lua_rawgeti(L_, -1, lua_Integer(index + 1));
  lua_remove(L_, -2);
}

void LuaValueMaker::push_number(std::string_view key) {
  if (sizes_work(key)) {
    const uint8_t b = in_.byte();
    if (b < 224) lua_pushinteger(L_, b % 9);
    else if (b >= 244 && (key == "width" || key == "height")) lua_pushnumber(L_, kHugeSides[b % std::size(kHugeSides)]);
    else lua_pushnumber(L_, kAbsurdCounts[b % std::size(kAbsurdCounts)]);
    return;
  }
  switch (in_.byte() % 8) {
    case 0:
    case 1:
    case 2: lua_pushinteger(L_, lua_Integer(in_.byte() % 21) - 5); break;
    case 3: lua_pushnumber(L_, double(int16_t(in_.u16())) / 64); break;
    case 4:
    case 5: lua_pushnumber(L_, kSpecial[in_.byte() % std::size(kSpecial)]); break;
    case 6: lua_pushnumber(L_, in_.f64()); break;
    default: {
      const uint8_t b = in_.byte();
      if (b < 128) lua_pushinteger(L_, lua_Integer(in_.u64()));
      else lua_pushinteger(L_, b & 1 ? std::numeric_limits<lua_Integer>::max() : std::numeric_limits<lua_Integer>::min());
    }
  }
}

void LuaValueMaker::push_string() {
  switch (in_.byte() % 4) {
    case 0:
    case 1: {
      const auto& w = torte_words();
      const std::string& s = w[in_.pick(w.size())];
      lua_pushlstring(L_, s.data(), s.size());
      break;
    }
    case 2: {
      const auto& k = torte_keywords();
      const std::string& s = k[in_.pick(k.size())];
      lua_pushlstring(L_, s.data(), s.size());
      break;
    }
    default: {
      // Raw bytes, with '/' replaced so that a string used as a file name stays in the scratch directory.
      std::string s(in_.bytes(24));
      std::replace(s.begin(), s.end(), '/', '_');
      lua_pushlstring(L_, s.data(), s.size());
    }
  }
}

void LuaValueMaker::push_kwargs(int depth, bool* only_known_keys) {
  const auto& keys = torte_keywords();
  const int n = in_.byte() % 7;
  lua_createtable(L_, 0, n);
  for (int i = 0; i < n; ++i) {
    const uint8_t b = in_.byte() % 16;
    std::string key;
    if (b < 13) {
      key = keys[in_.pick(keys.size())];
      lua_pushlstring(L_, key.data(), key.size());
    } else if (b == 13) {
      key = std::string(in_.bytes(12));
      lua_pushlstring(L_, key.data(), key.size());
    } else if (b == 14) {
      lua_pushinteger(L_, 1 + in_.byte() % 4);
    } else {
      lua_pushnumber(L_, 1.5);
    }
    push_value(depth + 1, key);
    lua_rawset(L_, -3);
  }
  // Judged on the finished table: a later nil can remove an entry.
  bool known = true;
  lua_pushnil(L_);
  while (lua_next(L_, -2) != 0) {
    lua_pop(L_, 1);
    if (lua_type(L_, -1) != LUA_TSTRING) {
      known = false;
    } else {
      size_t len = 0;
      const char* k = lua_tolstring(L_, -1, &len);
      if (std::find(keys.begin(), keys.end(), std::string_view(k, len)) == keys.end()) known = false;
    }
  }
  if (only_known_keys) *only_known_keys = known;
}

void LuaValueMaker::push_object() {
  if (slots_ && in_.byte() % 2) {
    lua_rawgeti(L_, slots_, 1 + in_.byte() % 16);
    return;
  }
  push_pool_entry("torte.fuzz.objects", in_.pick(pool_size(L_, "torte.fuzz.objects")));
  lua_call(L_, 0, 1);
}

void LuaValueMaker::push_function() {
  push_pool_entry("torte.fuzz.functions", in_.pick(pool_size(L_, "torte.fuzz.functions")));
}

void LuaValueMaker::push_value(int depth, std::string_view key) {
  luaL_checkstack(L_, 8, "fuzz value");
  const uint8_t kind = in_.byte() % 20;
  if (kind >= 18) {  // an object of the type this keyword takes, when it takes one
    lua_getfield(L_, LUA_REGISTRYINDEX, "torte.fuzz.typed");
    lua_pushlstring(L_, key.data(), key.size());
    if (lua_rawget(L_, -2) == LUA_TTABLE) {
      lua_rawgeti(L_, -1, lua_Integer(1 + in_.pick(lua_rawlen(L_, -1))));
      lua_call(L_, 0, 1);
      lua_replace(L_, -3);
      lua_pop(L_, 1);
      return;
    }
    lua_pop(L_, 2);
    push_number(key);
    return;
  }
  if (depth > 3 && (kind >= 9 && kind <= 11)) {  // no deeper tables
    push_number(key);
    return;
  }
  switch (kind) {
    case 0: lua_pushnil(L_); break;
    case 1: lua_pushboolean(L_, in_.byte() & 1); break;
    case 2:
    case 3:
    case 4: push_number(key); break;
    case 5:
    case 6: push_string(); break;
    case 7:
    case 8:
      lua_createtable(L_, 3, 0);
      for (int i = 1; i <= 3; ++i) {
        push_number();
        lua_rawseti(L_, -2, i);
      }
      break;
    case 9: {
      const int n = in_.byte() % 7;
      lua_createtable(L_, n, 0);
      for (int i = 1; i <= n; ++i) {
        push_value(depth + 1);
        lua_rawseti(L_, -2, i);
      }
      break;
    }
    case 10: {  // points {{x, y, z}, ...} or a flat array of numbers
      const int n = in_.byte() % 13;
      const bool nested = in_.byte() & 1;
      lua_createtable(L_, n, 0);
      for (int i = 1; i <= n; ++i) {
        if (nested) {
          lua_createtable(L_, 3, 0);
          for (int k = 1; k <= 3; ++k) {
            push_number();
            lua_rawseti(L_, -2, k);
          }
        } else {
          push_number();
        }
        lua_rawseti(L_, -2, i);
      }
      break;
    }
    case 11: push_kwargs(depth + 1); break;
    case 12:
    case 13: push_object(); break;
    case 14: push_function(); break;
    case 15:
      push_pool_entry("torte.fuzz.odd", in_.pick(pool_size(L_, "torte.fuzz.odd")));
      lua_call(L_, 0, 1);
      break;
    case 16:
      if (slots_) lua_rawgeti(L_, slots_, 1 + in_.byte() % 16);
      else push_object();
      break;
    default: lua_pushinteger(L_, lua_Integer(in_.u32())); break;
  }
}

}  // namespace torte::fuzz
