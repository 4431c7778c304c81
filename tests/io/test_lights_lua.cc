// torte.light.* and torte.camera.* from scripts through the built binary: an environment map written as .exr and
// .hdr with torte's image writer loads and renders, every new constructor works, and bad arguments are one-line
// errors naming the function and key.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

using namespace torte::test;

namespace {

struct LightDir : TempDir {
  explicit LightDir(const std::string& name) : TempDir("lights_lua", name) {}
};

Result run(const TempDir& dir, const std::vector<std::string>& args, double timeout = 30) {
  return run_torte(dir, args, timeout, dir.path.string());
}

}  // namespace

TEST_CASE("lights lua: an .exr and an .hdr environment map load and render", "[lights_lua]") {
  LightDir dir("env");
  torte::Image env(16, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) env.at(x, y) = torte::Rgb(0.25f, 0.5f, 0.125f);
  torte::write_image(env, dir / "env.exr");
  torte::write_image(env, dir / "env.hdr");
  const std::string script = dir.write("env.lua", R"(
for _, file in ipairs{"env.exr", "env.hdr"} do
  local scene = torte.scene()
  scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = 0.5}})
  scene:add(torte.light.environment{file = file, transform = torte.rotate(30, {0, 1, 0}), scale = 2})
  local image = torte.render{scene = scene, width = 16, height = 16, spp = 4,
                             camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 40}}
  local r, g, b = image:pixel(0, 0)
  print(string.format("%s %.4f %.4f %.4f", file, r, g, b))
end
)");
  const Result r = run(dir, {"--quiet", script});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto lines = lines_of(r.out);
  REQUIRE(lines.size() == 2);
  // The corner pixel sees the map times scale 2 (RGBE keeps ~1% precision).
  CHECK(lines[0] == "env.exr 0.5000 1.0000 0.2500");
  CHECK_THAT(lines[1], Catch::StartsWith("env.hdr 0.50"));
}

TEST_CASE("lights lua: every constructor, thin lens, and one-line errors", "[lights_lua]") {
  LightDir dir("errors");
  const std::string script = dir.write("lights.lua", R"(
local scene = torte.scene()
scene:add(torte.shape.polygon{points = {{-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}}})
scene:add(torte.light.spot{position = {0, 3, 0}, look_at = {0, 0, 0}, intensity = 10, angle = 25, falloff = 20})
scene:add(torte.light.directional{direction = {0.3, -1, 0.2}, irradiance = {1, 0.9, 0.8}})
scene:add(torte.light.sky{sun_elevation = 40, sun_azimuth = 30, turbidity = 4})
local cam = torte.camera.perspective{eye = {0, 2, -5}, look_at = {0, 0, 0}, fov = 40, aperture = 0.05}
local image = torte.render{scene = scene, camera = cam, width = 16, height = 12, spp = 2}
local r, g, b = image:mean()
print("ok", r > 0 and g > 0 and b > 0)
local function try(f, t)
  local ok, err = pcall(function() return f(t) end)
  print(ok and "no error" or err)
end
try(torte.light.spot, {position = {0, 1, 0}, angle = -5})
try(torte.light.spot, {position = {0, 1, 0}, angle = 20, falloff = 30})
try(torte.light.spot, {position = {0, 1, 0}, direction = {0, 0, 0}})
try(torte.light.directional, {direction = {0, 0, 0}})
try(torte.light.environment, {file = "no-such.exr"})
try(torte.light.sky, {sun_elevation = -10})
try(torte.light.sky, {turbidity = 30})
try(torte.light.sky, {sun_direction = {0, 1, 0}, sun_elevation = 10})
try(torte.camera.perspective, {aperture = -1})
try(torte.light.spot, {position = {0, 1, 0}, angel = 3})
)");
  const Result r = run(dir, {"--quiet", script});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto lines = lines_of(r.out);
  REQUIRE(lines.size() == 11);
  CHECK(lines[0] == "ok\ttrue");
  const std::vector<std::string> expect = {
      "torte.light.spot: 'angle' must be in (0, 180] degrees",
      "torte.light.spot: 'falloff' must be in [0, angle] degrees",
      "torte.light.spot: 'direction' must be a non-zero vector",
      "torte.light.directional: 'direction' must be a non-zero vector",
      "torte.light.environment: ",
      "torte.light.sky: 'sun_elevation' must be in [0, 90] degrees",
      "torte.light.sky: 'turbidity' must be in [1.7, 10]",
      "torte.light.sky: 'sun_direction' cannot be combined",
      "torte.camera.perspective: 'aperture' must be finite and non-negative",
      "torte.light.spot: unknown key 'angel'",
  };
  for (size_t i = 0; i < expect.size(); ++i) {
    INFO(lines[i + 1]);
    CHECK_THAT(lines[i + 1], Catch::Contains(expect[i]));
    CHECK_THAT(lines[i + 1], Catch::Contains("lights.lua:"));
  }
  CHECK_THAT(lines[5], Catch::Contains("no-such.exr"));
  // Through the binary, an error is one line on stderr naming file and line.
  const std::string bad = dir.write("bad.lua", "-- 1\nlocal l = torte.light.environment{file = 'missing.hdr'}\n");
  const std::string line = check_error(run(dir, {"--quiet", bad}));
  CHECK_THAT(line, Catch::Contains("bad.lua:2: torte.light.environment"));
  CHECK_THAT(line, Catch::Contains("missing.hdr"));
}

TEST_CASE("lights lua: scenes/lights.lua renders every light type and a thin lens", "[lights_lua][scenes]") {
  LightDir dir("scene");
  const std::string scene = std::string(TORTE_SOURCE_DIR) + "/scenes/lights.lua";
  const Result r = run(dir, {"--quiet", scene, "width=32", "height=24", "spp=2", "max_depth=2", "light=all",
                             "aperture=0.1", "output=" + (dir / "out/all.exr")});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(std::filesystem::exists(dir / "out/all.exr"));
  CHECK(std::filesystem::exists(dir / "out/lights-env.exr"));  // the generated environment map
  const Result bad = run(dir, {"--quiet", scene, "light=moon", "output=" + (dir / "x.exr")});
  CHECK(bad.code == 1);
  CHECK_THAT(bad.err, Catch::Contains("argument 'light' must be"));
}

// Textured area lights: `emission = texture` is the radiance at each point, for rays that hit the emitter and for
// light samples (next-event estimation, light subpaths) alike, so path and bdpt agree.
TEST_CASE("lights lua: a textured emitter emits its texture, seen and sampled", "[lights_lua]") {
  LightDir dir("textured_emission");
  const std::string script = dir.write("textured.lua", R"(
local torte = require "torte"
local T = torte.texture
local function quad(y, half, material, emission, down)
  local p = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}}
  return torte.shape.mesh{positions = p, indices = down and {0, 1, 2, 0, 2, 3} or {0, 2, 1, 0, 3, 2},
                          uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, material = material, emission = emission}
end
local function floor_mean(emission, integrator, spp)
  local scene = torte.scene()
  scene:add(quad(0, 3, torte.material.matte{color = 0.5}))
  scene:add(quad(1, 1, torte.material.matte{color = 0}, emission, true))
  local camera = torte.camera.perspective{eye = {0, 0.5, 0}, look_at = {0, 0, 0}, up = {0, 0, 1}, fov = 20}
  local img = torte.render{scene = scene, camera = camera, width = 16, height = 16, spp = spp or 64, max_depth = 1,
                           integrator = integrator or "path"}
  return (img:mean())
end
local uniform = floor_mean(1)
assert(uniform > 0.01, "uniform " .. uniform)
-- A constant texture is its value as a colour.
local c = floor_mean(T.constant{value = 3})
assert(math.abs(c / uniform - 3) < 0.05, "constant texture: " .. c / uniform)
-- A checker of 0 and 2 in 16 x 16 cells averages 1 over the emitter: nearly the uniform floor.
local checker = floor_mean(T.checker{a = 0, b = 2, scale = 16})
assert(math.abs(checker / uniform - 1) < 0.05, "checker: " .. checker / uniform)
-- Light subpaths (bdpt) start on the texture too: the same image as path's.
local bdpt = floor_mean(T.checker{a = 0, b = 2, scale = 16}, "bdpt", 256)
assert(math.abs(bdpt / checker - 1) < 0.05, "bdpt against path: " .. bdpt / checker)
-- Seen directly from below: the texture's value.
local scene = torte.scene():add(quad(1, 1, torte.material.matte{color = 0}, T.constant{value = 3}, true))
local up = torte.camera.perspective{eye = {0, 0.5, 0}, look_at = {0, 1, 0}, up = {0, 0, 1}, fov = 20}
local seen = (torte.render{scene = scene, camera = up, width = 8, height = 8, spp = 1}:mean())
assert(math.abs(seen - 3) < 1e-4, "seen: " .. seen)
print(("ok %.4f %.4f %.4f %.4f"):format(uniform, c, checker, bdpt))
)");
  const Result r = run_torte(dir, {"--quiet", script}, 120);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::StartsWith("ok"));
}
