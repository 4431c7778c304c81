// torte.texture from scripts (through the built binary) and from C++ (the Lua helpers materials use, and image
// textures through OpenImageIO): operators build the right graph, type errors name the function, key, file and
// line, the spot texture reads the texels OpenImageIO reads, and a missing image is a one-line error.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "test_support.h"
#include "texture/image_texture_oiio.h"
#include "texture/texture.h"
#include "texture_param.h"
#include "types.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct TexDir : TempDir {
  explicit TexDir(const std::string& name) : TempDir("texture_lua", name) {}
};

Result run(const TempDir& dir, const std::vector<std::string>& args, double timeout = 30) {
  return run_torte(dir, args, timeout, dir.path.string());
}

const std::string kSpot = std::string(TORTE_SOURCE_DIR) + "/../shared/data/meshes/spot/spot_texture.png";

// A Lua state with the torte bindings' texture functions, for calling the C++ helpers directly.
struct LuaState {
  lua_State* L = luaL_newstate();
  LuaState() {
    luaL_openlibs(L);
    lua_newtable(L);
    torte::lua::open_textures(L, lua_gettop(L));
    lua_setglobal(L, "torte");
  }
  ~LuaState() { lua_close(L); }
  // Runs `code`, which must leave one table (keyword arguments) on the stack.
  void push(const std::string& code) {
    REQUIRE(luaL_dostring(L, ("return " + code).c_str()) == LUA_OK);
    REQUIRE(lua_istable(L, -1));
  }
};

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const torte::Error& e) {
    return e.what();
  }
  return "(no error)";
}

inline float srgb_decode(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

}  // namespace

TEST_CASE("texture lua: operators and constructors build the right graph", "[texture_lua]") {
  TexDir dir("operators");
  const std::string script = dir.write("scene.lua", R"(
local T = torte.texture
local function near(a, b) return math.abs(a - b) < 1e-5 end
local c = T.checker{a = {1, 0, 0}, b = 0.25} .. T.uv{scale = 4}
assert(c.type == "color" and c.input == "none" and c.kind == "compose", tostring(c))
local v = c:eval{uv = {0.1, 0.1}}
assert(v[1] == 1 and v[2] == 0 and v[3] == 0)
v = c:eval{uv = {0.3, 0.1}}
assert(v[1] == 0.25 and v[3] == 0.25)
-- texture * number, number * texture, + number, - and / all build nodes
local s = 0.5 * c + 0.1
assert(s.kind == "add" and s.type == "color")
assert(near(s:eval{uv = {0.1, 0.1}}[1], 0.6))
assert(near((c * 2):eval{uv = {0.3, 0.1}}[2], 0.5))
assert(near((c / 4 - 0.0625):eval{uv = {0.3, 0.1}}[1], 0))
assert(near((c * {1, 2, 4}):eval{uv = {0.3, 0.1}}[3], 1))
local tt = T.checker{a = 2, b = 3} * T.checker{a = 5, b = 7}
assert(tt.kind == "multiply" and tt.type == "float" and tt.input == "vec2", tt.input)
assert(tt:eval{uv = {0.5, 0.5}} == 10 and tt:eval{input = {1.5, 0.5}} == 21)
local mixed = T.checker{a = 2, b = 3} * T.fbm{}   -- vec2 and vec3 inputs: each takes its default
assert(mixed.input == "none" and math.abs(mixed:eval{uv = {0.5, 0.5}, p = {0.1, 0.2, 0.3}} - 2 * T.fbm{}:eval{p = {0.1, 0.2, 0.3}}) < 1e-6)
-- composition with .. : spline o fbm o xyz
local n = T.fbm{octaves = 4, seed = 2}
assert(n.input == "vec3" and n.type == "float")
local marble = T.spline{colors = {0, 1}, interpolation = "linear"} .. n .. T.xyz{transform = torte.scale(2, 2, 2)}
assert(marble.input == "none" and marble.type == "color")
local x = n:eval{input = {0.15, 0.1, 0.05}}
assert(near(marble:eval{p = {0.3, 0.2, 0.1}}[2], x), "spline o fbm o xyz")
assert(near(n:eval{p = {0.15, 0.1, 0.05}}, x), "3D noise reads p by default")
assert(T.grayscale().input == "float" and (T.grayscale() .. 0.5):eval{}[3] == 0.5)
local l = T.lerp{t = T.checker{a = 0, b = 1}, a = {1, 1, 1}, b = {0, 0, 0}}
assert(l:eval{uv = {1.5, 0.5}}[1] == 0 and l:eval{uv = {0.5, 0.5}}[1] == 1)
assert(T.mix{t = 0.5, a = 0, b = 2}:eval{} == 1)
assert(T.compose{outer = T.perlin{dims = 2}, inner = T.uv{}}.input == "none")
assert(T.add{a = 1, b = 2}:eval{} == 3 and T.multiply{a = 2, b = 4}:eval{} == 8)
assert(T.scale{texture = 3, factor = 2}:eval{} == 6 and T.constant{value = {1, 2, 3}}:eval{}[2] == 2)
local sp = T.spherical{}:eval{p = {0, 0, 1}}
assert(near(sp[1], 0.25) and near(sp[2], 0.5))
assert(near(T.cylindrical{}:eval{p = {0, 3, 1}}[2], 3))
assert(near(T.planar{s = {1, 0, 0}, t = {0, 0, 1}, offset = {1, 0}}:eval{p = {1, 2, 3}}[1], 2))
local c3 = T.checker3d{a = 1, b = 0}
assert(c3:eval{p = {0.5, 0.5, 0.5}} == 1 and c3:eval{p = {1.5, 0.5, 0.5}} == 0)
local vn = T.value_noise{dims = 2}
local r = vn:eval{uv = {0.3, 0.7}}
assert(r >= 0 and r <= 1)
local tu = T.turbulence{basis = "value", octaves = 3, lacunarity = 2.5, gain = 0.4}
assert(tu:eval{p = {0.1, 0.2, 0.3}} >= 0)
print("ok " .. tostring(marble))
)");
  const Result r = run(dir, {"--quiet", script});
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("ok torte.texture (compose: none -> color)"));
}

TEST_CASE("texture lua: type errors name the function, key, file and line", "[texture_lua]") {
  struct Case {
    std::string code, expect;
  };
  const std::vector<Case> cases = {
      {"local t = torte.texture.perlin{dims = 3} .. torte.texture.uv{}",
       "torte.texture operator .. (compose): the outer texture (noise) takes a 3D-vector input but the inner "
       "texture (uv) gives a 2D-vector value"},
      {"local t = torte.texture.checker{a = torte.texture.uv{}}",
       "torte.texture.checker: 'a' must be a scalar or colour texture, got a 2D-vector texture"},
      {"local t = torte.texture.fbm{octave = 3}", "torte.texture.fbm: unknown key 'octave'"},
      {"local t = torte.texture.lerp{t = {1, 0, 0}, a = 0, b = 1}",
       "torte.texture.lerp: 't' must be a scalar texture, got a colour texture"},
      {"local t = torte.texture.uv{} + 1",
       "torte.texture operator +: 'a' must be a scalar or colour texture, got a 2D-vector texture"},
      {"local t = torte.texture.checker{} * 'x'",
       "torte.texture operator *: operands must be torte.texture values, numbers or {r, g, b} colours, got string"},
      {"local t = torte.texture.grayscale():eval{}", "takes a scalar input and cannot be used on its own"},
      {"local t = torte.texture.image{file = 'x.png', wrap = 'tile'}", "torte.texture.image: 'wrap' must be"},
  };
  // In-process (a torte process costs ~0.4 s to start); the chunk is named like a file, as torte does.
  LuaState s;
  for (const Case& c : cases) {
    INFO(c.code);
    const std::string code = "-- line 1\n" + c.code + "\n";
    REQUIRE(luaL_loadbuffer(s.L, code.data(), code.size(), "@bad.lua") == LUA_OK);
    REQUIRE(lua_pcall(s.L, 0, 0, 0) != LUA_OK);
    const std::string message = lua_tostring(s.L, -1);
    lua_pop(s.L, 1);
    CHECK_THAT(message, Catch::StartsWith("bad.lua:2: "));
    CHECK_THAT(message, Catch::Contains(c.expect));
  }
  // Through the binary: one line on stderr and exit code 1.
  TexDir dir("errors");
  const std::string script = dir.write("bad.lua", "-- line 1\n" + cases[0].code + "\n");
  const std::string line = check_error(run(dir, {"--quiet", script}));
  CHECK_THAT(line, Catch::Contains("bad.lua:2: " + cases[0].expect));
}

TEST_CASE("texture lua: float_input and color_input for material keys", "[texture_lua]") {
  using namespace torte;
  LuaState s;
  s.push("{roughness = 0.3, color = {0.1, 0.2, 0.3}}");
  {
    lua::KwArgs kw(s.L, -1, "torte.material.plastic");
    const FloatInput f = lua::float_input(kw, "roughness", 0.5f);
    CHECK(f.value == Approx(0.3f));
    CHECK(!f.texture);
    const ColorInput c = lua::color_input(kw, "color", Rgb(0.5f));
    CHECK(c.value == Rgb(0.1f, 0.2f, 0.3f));
    const FloatInput d = lua::float_input(kw, "absent", 0.5f);
    CHECK(d.value == 0.5f);
    CHECK_NOTHROW(kw.finish());  // every key was read
  }
  lua_settop(s.L, 0);
  s.push("{roughness = torte.texture.checker{a = {1, 0, 0}}, color = torte.texture.fbm{}, "
         "k = torte.texture.spline{colors = {0, 1}}, v = torte.texture.uv{}, w = 'x', c = -1}");
  lua::KwArgs kw(s.L, -1, "torte.material.plastic");
  CHECK(lua::is_texture(s.L, -1) == false);
  lua_getfield(s.L, -1, "color");
  CHECK(lua::is_texture(s.L, -1));
  lua_pop(s.L, 1);
  CHECK(error_of([&] { lua::float_input(kw, "roughness", 0); }) ==
        "torte.material.plastic: 'roughness' expects a scalar texture, got a colour texture");
  const ColorInput scalar_as_colour = lua::color_input(kw, "color", Rgb());  // a scalar texture is grey
  REQUIRE(scalar_as_colour.texture);
  CHECK(scalar_as_colour.texture->output == ValueType::Float);
  CHECK_THAT(error_of([&] { lua::color_input(kw, "k", Rgb()); }),
             Catch::Contains("'k' got a spline texture that takes a scalar input"));
  CHECK(error_of([&] { lua::color_input(kw, "v", Rgb()); }) ==
        "torte.material.plastic: 'v' expects a colour or scalar texture, got a 2D-vector texture");
  CHECK(error_of([&] { lua::float_input(kw, "w", 0); }) ==
        "torte.material.plastic: 'w' expects a number or a scalar torte.texture, got string");
  CHECK_THAT(error_of([&] { lua::color_input(kw, "c", Rgb()); }), Catch::Contains("'c' must be finite and non-negative"));
  // The texture of a FloatInput evaluates through a table like any other.
  const FloatInput ok = lua::float_input(kw, "color", 0);
  TextureTableBuilder b;
  const FloatParam p = b.add(ok);
  const TextureTable t = b.finish();
  TextureContext ctx;
  ctx.p = {0.3f, 0.2f, 0.1f};
  NoiseParams np;
  np.fractal = NoiseFractal::Fbm;
  CHECK(t.eval(p, ctx) == noise_texture(np, ctx.p));
}

TEST_CASE("texture lua: the spot image texture reads the texels OpenImageIO reads", "[texture_lua]") {
  if (!fs::exists(kSpot)) {
    WARN("SKIP: " << kSpot << " not found (../shared/data is absent)");
    return;
  }
  auto in = OIIO::ImageInput::open(kSpot);
  REQUIRE(in);
  const OIIO::ImageSpec spec = in->spec();
  REQUIRE(spec.format == OIIO::TypeDesc::UINT8);
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  REQUIRE(nc >= 3);
  std::vector<unsigned char> pixels(size_t(w) * size_t(h) * size_t(nc));
  REQUIRE(in->read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, pixels.data()));
  in->close();

  torte::ImageTextureOptions raw_opt;
  raw_opt.filter = torte::ImageTextureOptions::Filter::Closest;
  raw_opt.color_space = torte::ImageTextureOptions::ColorSpace::Linear;
  torte::ImageTextureOptions srgb_opt = raw_opt;
  srgb_opt.color_space = torte::ImageTextureOptions::ColorSpace::Auto;  // 8-bit PNG: sRGB
  const auto raw = torte::open_image_texture(kSpot, raw_opt);
  const auto lin = torte::open_image_texture(kSpot, srgb_opt);
  CHECK_THAT(lin->description(), Catch::Contains("sRGB"));
  // uv (0, 0) is the bottom-left: texel column x, row y from the top is at uv ((x + .5) / w, 1 - (y + .5) / h).
  const int probes[][2] = {{0, 0}, {w - 1, h - 1}, {w / 2, h / 4}, {w / 5, (3 * h) / 4}, {123, 456}, {900, 77}};
  int distinct = 0;
  for (const auto& xy : probes) {
    const int x = xy[0], y = xy[1];
    INFO("texel " << x << ", " << y);
    const torte::Vec2f st((x + 0.5f) / float(w), 1 - (y + 0.5f) / float(h));
    const unsigned char* px = &pixels[(size_t(y) * size_t(w) + size_t(x)) * size_t(nc)];
    const torte::Rgb a = raw->lookup(st, 0), b = lin->lookup(st, 0);
    CHECK(a.r == Approx(px[0] / 255.0f).margin(1e-4));
    CHECK(a.g == Approx(px[1] / 255.0f).margin(1e-4));
    CHECK(a.b == Approx(px[2] / 255.0f).margin(1e-4));
    CHECK(b.r == Approx(srgb_decode(px[0] / 255.0f)).margin(1e-4));
    CHECK(b.b == Approx(srgb_decode(px[2] / 255.0f)).margin(1e-4));
    // The vertically mirrored texel is different somewhere, so a missing flip would be caught.
    const unsigned char* mirrored = &pixels[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * size_t(nc)];
    distinct += mirrored[0] != px[0] || mirrored[1] != px[1] || mirrored[2] != px[2];
  }
  CHECK(distinct >= 3);
  // Trilinear with a footprint stays close to the texel average and inside the image's range; periodic wrap.
  torte::ImageTextureOptions tri;
  const auto t = torte::open_image_texture(kSpot, tri);
  const torte::Rgb c = t->lookup({0.3f, 0.6f}, 0.01f), wrapped = t->lookup({1.3f, 0.6f}, 0.01f);
  CHECK(c.is_finite());
  CHECK(c.max_component() <= 1.0f);
  CHECK(wrapped.r == Approx(c.r).margin(1e-5));

  // The same lookups from Lua, through torte.texture.image and :eval.
  TexDir dir("spot");
  const int x = w / 2, y = h / 4;
  const unsigned char* px = &pixels[(size_t(y) * size_t(w) + size_t(x)) * size_t(nc)];
  const std::string script = dir.write(
      "scene.lua", "local t = torte.texture.image{file = '" + kSpot +
                       "', filter = 'closest', color_space = 'linear'}\n"
                       "local v = t:eval{uv = {" + std::to_string((x + 0.5) / w) + ", " +
                       std::to_string(1 - (y + 0.5) / h) + "}}\n"
                       "print(string.format('%d %d %d', math.floor(v[1] * 255 + 0.5), math.floor(v[2] * 255 + 0.5), "
                       "math.floor(v[3] * 255 + 0.5)))\n");
  const Result r = run(dir, {"--quiet", script});
  check_no_crash(r);
  CHECK(r.code == 0);
  CHECK(r.out == std::to_string(px[0]) + " " + std::to_string(px[1]) + " " + std::to_string(px[2]) + "\n");
}

TEST_CASE("texture lua: a missing or corrupt image file is a one-line error", "[texture_lua]") {
  TexDir dir("missing");
  dir.write("garbage.png", "this is not a png file at all");
  const std::string missing = dir.write("missing.lua", "-- x\nlocal t = torte.texture.image{file = 'no-such.png'}\n");
  std::string line = check_error(run(dir, {"--quiet", missing}));
  CHECK_THAT(line, Catch::Contains("missing.lua:2: torte.texture.image: cannot open image texture 'no-such.png'"));
  const std::string corrupt = dir.write("corrupt.lua", "local t = torte.texture.image{file = 'garbage.png'}\n");
  line = check_error(run(dir, {"--quiet", corrupt}));
  CHECK_THAT(line, Catch::Contains("corrupt.lua:1: torte.texture.image: cannot read image texture 'garbage.png'"));
  CHECK_THROWS_AS(torte::open_image_texture((dir.path / "garbage.png").string(), {}), torte::Error);
}
