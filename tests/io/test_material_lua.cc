// torte.material.* from Lua: every constructor builds a material that renders (no NaN), and bad parameters give
// one clear error naming the function, the key and the script line. The error cases run in one script through
// pcall (one process), plus one real failing run for the exit code and the one-line format.
#include <catch2/catch.hpp>

#include "test_support.h"

using namespace torte::test;

namespace {
struct MaterialDir : TempDir {
  explicit MaterialDir(const std::string& name) : TempDir("material", name) {}
};
}  // namespace

TEST_CASE("materials: every constructor renders without NaN samples", "[lua][material]") {
  MaterialDir dir("all");
  const std::string script = dir.write("all.lua", R"(
local torte = require "torte"
local M = torte.material
local materials = {
  M.matte{color = {0.8, 0.5, 0.2}}, M.matte{color = 0.5, sigma = 20}, M.lambert{},
  M.plastic{color = {0.6, 0.1, 0.1}, roughness = 0.3, eta = 1.6}, M.plastic{roughness = 0},
  M.metal{metal = "gold", roughness = 0.2}, M.metal{metal = "Cu", roughness_u = 0.1, roughness_v = 0.4},
  M.metal{eta = {0.2, 0.9, 1.1}, k = {3.9, 2.4, 2.1}, roughness = 0, distribution = "beckmann"},
  M.mirror{color = 0.9}, M.glass{eta = 1.5}, M.glass{thin = true, color = {0.9, 1, 0.9}},
  M.rough_glass{eta = 1.33, roughness = 0.3}, M.mix{a = M.mirror{}, b = M.matte{}, amount = 0.3},
  M.bump{material = M.matte{}, height = 0.01}, M.bump{material = M.plastic{}, normal_map = {0.7, 0.4, 0.9}},
}
local scene = torte.scene()
for i, m in ipairs(materials) do
  scene:add(torte.shape.sphere{radius = 0.4, transform = torte.translate((i - 7.5) * 0.9, 0, 0), material = m})
end
scene:add(torte.light.infinite{radiance = 1})
scene:add(torte.light.point{position = {0, 5, -5}, intensity = 20})
local img = torte.render{scene = scene, camera = torte.camera.orthographic{eye = {0, 0, -5}, extent = 14},
                         width = 140, height = 10, spp = 4, max_depth = 8}
print(("mean=%.4f"):format(img:mean()))
)");
  const Result r = run_torte(dir, {"--quiet", script}, 60);
  check_no_crash(r);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("mean="));
  CHECK_THAT(r.err, !Catch::Contains("NaN/Inf samples were dropped"));
}

TEST_CASE("materials: bad parameters name the function, the key and the line", "[lua][material]") {
  MaterialDir dir("bad");
  // Each line is one call expected to fail; the script prints each error message on its own line.
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"M.plastic{roughness = -0.1}", {"torte.material.plastic", "'roughness'"}},
      {"M.metal{roughness = 1.5}", {"torte.material.metal", "'roughness'"}},
      {"M.glass{eta = 0}", {"torte.material.glass", "'eta'"}},
      {"M.rough_glass{eta = -1.5}", {"torte.material.rough_glass", "'eta'"}},
      {"M.matte{color = {1.5, 0, 0}}", {"torte.material.matte", "'color'"}},
      {"M.matte{sigma = 120}", {"torte.material.matte", "'sigma'"}},
      {"M.metal{metal = 'unobtainium'}", {"torte.material.metal", "'metal'", "gold"}},
      {"M.metal{metal = 'gold', eta = 1}", {"torte.material.metal", "'metal'"}},
      {"M.metal{distribution = 'phong'}", {"torte.material.metal", "'distribution'"}},
      {"M.mix{a = M.matte{}, b = 3}", {"torte.material.mix", "'b'"}},
      {"M.mix{a = M.matte{}, b = M.matte{}, amount = 2}", {"torte.material.mix", "'amount'"}},
      {"M.bump{height = 1}", {"torte.material.bump", "'material'"}},
      {"M.bump{material = M.matte{}, height = 1, normal_map = 0.5}", {"torte.material.bump", "'normal_map' and 'height'"}},
      {"M.plastic{colour = 0.5}", {"torte.material.plastic", "'colour'"}},
      {"M.plastic{roughness = torte.texture.uv{}}", {"torte.material.plastic", "'roughness'", "scalar"}},
      {"M.matte{color = torte.texture.uv{}}", {"torte.material.matte", "'color'"}},
  };
  std::string script = "local torte = require 'torte'\nlocal M = torte.material\n";
  for (const auto& [call, _] : cases)
    script += "print((select(2, pcall(function() return " + call + " end)) or 'no error'):gsub('\\n', ' '))\n";
  const std::string path = dir.write("bad.lua", script);
  const Result r = run_torte(dir, {"--quiet", path}, 30);
  check_no_crash(r);
  const std::vector<std::string> lines = lines_of(r.out);
  REQUIRE(lines.size() == cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    INFO("call: " << cases[i].first << "\nmessage: " << lines[i]);
    CHECK_THAT(lines[i], Catch::Contains(path + ":" + std::to_string(i + 3) + ":"));
    for (const std::string& part : cases[i].second) CHECK_THAT(lines[i], Catch::Contains(part));
  }
}

TEST_CASE("materials: a bad parameter stops the script with one line and a non-zero exit", "[lua][material]") {
  MaterialDir dir("exit");
  const std::string path = dir.write("bad.lua", "local torte = require 'torte'\n\nlocal g = torte.material.glass{eta = -2}\n");
  const std::string line = check_error(run_torte(dir, {path}, 30));
  CHECK_THAT(line, Catch::Contains(path + ":3:"));
  CHECK_THAT(line, Catch::Contains("'eta'"));
}

// A normal map tilts the shading normal: a constant map (0.5 + 0.5 sin a, 0.5, 0.5 + 0.5 cos a) turns it by a
// towards dp/du, so a Lambertian quad lit straight on is cos(a) as bright; x and y scale by `scale`; the flat
// map (0.5, 0.5, 1) changes nothing; and +y follows dp/dv.
TEST_CASE("materials: a normal map turns the shading normal in the dp/du, dp/dv frame", "[lua][material]") {
  MaterialDir dir("normal_map");
  const std::string script = dir.write("normal_map.lua", R"(
local torte = require "torte"
local M = torte.material
-- A unit quad in z = 0 facing +z with u along +x and v along +y, lit along -z; an orthographic camera on +z.
local function brightness(material, light_dir)
  local scene = torte.scene()
  scene:add(torte.shape.mesh{positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, indices = {0, 1, 2, 0, 2, 3},
                             uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, material = material})
  scene:add(torte.light.directional{direction = light_dir or {0, 0, -1}, irradiance = 1})
  local img = torte.render{scene = scene, camera = torte.camera.orthographic{eye = {0, 0, 5}, look_at = {0, 0, 0}, extent = 1},
                           width = 8, height = 8, spp = 1, max_depth = 1}
  return img:mean()
end
local a = math.rad(60)
local matte = M.matte{color = 0.5}
local flat = brightness(matte)
local tilted_map = {0.5 + 0.5 * math.sin(a), 0.5, 0.5 + 0.5 * math.cos(a)}
assert(math.abs(flat - 0.5 / math.pi) < 1e-3, "flat " .. flat)
assert(math.abs(brightness(M.bump{material = matte, normal_map = {0.5, 0.5, 1}}) - flat) < 1e-6, "identity map")
local tilted = brightness(M.bump{material = matte, normal_map = tilted_map})
assert(math.abs(tilted / flat - math.cos(a)) < 1e-3, "tilted by 60 degrees: " .. tilted / flat)
-- scale = 0 flattens the tilt away
assert(math.abs(brightness(M.bump{material = matte, normal_map = tilted_map, scale = 0}) - flat) < 1e-6, "scale 0")
-- Light from +x (travelling towards -x and -z): the normal turned towards +x (dp/du) sees it head on.
local oblique = {-math.sin(a), 0, -math.cos(a)}
assert(math.abs(brightness(M.bump{material = matte, normal_map = tilted_map}, oblique) / flat - 1) < 1e-3, "towards +u")
-- The same tilt towards +y (green) faces a light from +y.
local up_map = {0.5, 0.5 + 0.5 * math.sin(a), 0.5 + 0.5 * math.cos(a)}
local from_up = {0, -math.sin(a), -math.cos(a)}
assert(math.abs(brightness(M.bump{material = matte, normal_map = up_map}, from_up) / flat - 1) < 1e-3, "towards +v")
print("ok")
)");
  const Result r = run_torte(dir, {"--quiet", script}, 60);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
}

// Cut-outs (torte.material.mask): a quad between a floor and a light from above, seen from between them (its
// shadow) and from above (the quad itself or the floor through it), for every kind of ray and integrator.
TEST_CASE("materials: mask cuts a surface out for camera, extension and shadow rays", "[lua][material]") {
  MaterialDir dir("mask");
  const std::string script = dir.write("mask.lua", R"(
local torte = require "torte"
local M = torte.material
local function quad(y, half, material)
  return torte.shape.mesh{positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}},
                          indices = {0, 2, 1, 0, 3, 2}, uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, material = material}
end
-- eye_y 0.5: under the blocker, the floor's shadow; 5: above it, the blocker (reflectance 0.1) or the floor (0.5).
local function mean(blocker, eye_y, integrator)
  local scene = torte.scene()
  scene:add(quad(0, 2, M.matte{color = 0.5}))
  if blocker then scene:add(quad(1, 3, blocker)) end
  -- Far above: irradiance 1 on the floor under it (bdpt connects to point lights, not to directional ones).
  scene:add(torte.light.point{position = {0, 50, 0}, intensity = 2500})
  local camera = torte.camera.perspective{eye = {0, eye_y, 0}, look_at = {0, 0, 0}, up = {0, 0, 1}, fov = 20}
  local img = torte.render{scene = scene, camera = camera, width = 16, height = 16, spp = 16, max_depth = 3,
                           integrator = integrator or "path"}
  return (img:mean())
end
local dark = M.matte{color = 0.1}
local lit = 0.5 / math.pi
local function near(a, b, tol, what) assert(math.abs(a - b) <= tol, ("%s: %.5f, expected %.5f"):format(what, a, b)) end
near(mean(nil, 0.5), lit, 1e-4, "no blocker")
near(mean(dark, 0.5), 0, 1e-6, "opaque blocker: shadow")
near(mean(M.mask{material = dark, alpha = 0}, 0.5), lit, 1e-4, "alpha 0: no shadow")
near(mean(M.mask{material = dark, alpha = 1}, 0.5), 0, 1e-6, "alpha 1: shadow")
near(mean(M.mask{material = dark, alpha = 0.4, cutoff = 0.5}, 0.5), lit, 1e-4, "below the cutoff")
near(mean(dark, 5), 0.1 / math.pi * (50 / 49) ^ 2, 1e-4, "the blocker from above, 49 below the light")
near(mean(M.mask{material = dark, alpha = 0}, 5), lit, 1e-4, "the floor through the cut-out")
-- A checker of alpha 0 and 1 in 20 x 20 cells: half the shadow.
local checker = M.mask{material = dark, alpha = torte.texture.checker{a = 0, b = 1, scale = 20}}
near(mean(checker, 0.5), 0.5 * lit, 0.05 * lit, "checker shadow")
-- Stochastic: present with probability alpha.
near(mean(M.mask{material = dark, alpha = 0.3, stochastic = true}, 0.5), 0.7 * lit, 0.04 * lit, "stochastic shadow")
-- Other integrators trace through the same scene functions.
for _, integrator in ipairs{"direct", "bdpt", "vcm"} do
  near(mean(M.mask{material = dark, alpha = 0}, 0.5, integrator), lit, 0.1 * lit, integrator .. ", alpha 0")
  near(mean(M.mask{material = dark, alpha = 1}, 0.5, integrator), 0, 0.02 * lit, integrator .. ", alpha 1")
end
-- An emitter cannot be cut out (its light would be sampled where it is absent).
local ok, err
local s = torte.scene()
s:add(torte.shape.sphere{material = M.mask{material = dark, alpha = 0.5}, emission = 1})
ok, err = pcall(torte.render, {scene = s, camera = torte.camera.perspective{eye = {0, 0, -4}}, width = 4, height = 4, spp = 1})
assert(not ok and err:find("cannot have a cut%-out"), tostring(err))
ok, err = pcall(M.mask, {material = dark, alpha = 2})
assert(not ok and err:find("'alpha' must be in %[0, 1%]"), tostring(err))
print("ok")
)");
  const Result r = run_torte(dir, {"--quiet", script}, 120);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
}
