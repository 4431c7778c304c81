// OBJ files with MTL materials from scripts, through the built binary: torte.shape.mesh{file=...} takes the MTL
// materials (one shape per material, Ke as area lights) unless the script passes a material, torte.mesh.load
// returns them, missing and unknown materials are warnings naming file and line, damaged MTL files are one-line
// errors, and the real cornell_box.obj renders lit.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct ObjDir : TempDir {
  explicit ObjDir(const std::string& name) : TempDir("obj_mtl", name) {}
};

Result run(const TempDir& dir, const std::vector<std::string>& args, double timeout = 60) {
  return run_torte(dir, args, timeout, dir.path.string());
}

// Two quads facing -z at z = 0: the left one red matte, the right one an emitter of radiance 3 (Ke).
const char kQuadsObj[] =
    "mtllib quads.mtl\n"
    "v -2 -1 0\nv 0 -1 0\nv 0 1 0\nv -2 1 0\nv 0 -1 0\nv 2 -1 0\nv 2 1 0\nv 0 1 0\n"
    "usemtl red\nf 1 4 3 2\nusemtl lamp\nf 5 8 7 6\n";
const char kQuadsMtl[] =
    "newmtl red\nKd 0.8 0.1 0.1\nKa 0 0 0\nillum 2\n"
    "newmtl lamp\nKd 0 0 0\nKe 3 3 3\nKs 0.5 0.5 0.5\nNs 100\nNi 1.4\nd 0.9\n";

}  // namespace

TEST_CASE("obj mtl lua: materials, emission, load and an override", "[obj_mtl]") {
  ObjDir dir("materials");
  dir.write("quads.obj", kQuadsObj);
  dir.write("quads.mtl", kQuadsMtl);
  const std::string script = dir.write("scene.lua", R"(
local shapes = torte.shape.mesh{file = "quads.obj"}
assert(type(shapes) == "table" and #shapes == 2, "one shape per material")
local mesh, mats = torte.mesh.load("quads.obj")
assert(mesh.triangles == 4 and #mats == 2, tostring(mesh))
assert(mats.red == mats[1] and mats[1].name == "red" and mats.lamp.emission[1] == 3)
assert(mats.red.mesh.triangles == 2 and mats.lamp.mesh.triangles == 2)
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 50}
local function render(scene)
  return torte.render{scene = scene, camera = camera, width = 16, height = 8, spp = 16, integrator = "path"}
end
local scene = torte.scene()
scene:add(shapes)
local img = render(scene)
-- torte's image x runs towards world -x here (camera +x is the image's left): the lamp (x > 0) is on the left.
local lamp, red = img:pixel(4, 4), img:pixel(11, 4)
-- The lamp is seen directly (radiance 3); the red quad, in the lamp's plane, gets none of its light.
assert(lamp > 2.5 and lamp < 3.5, "emitter: " .. lamp)
assert(red < lamp / 4, "lit by the lamp only: " .. red)
-- A material of the script's own replaces the MTL's, and then Ke makes no light.
local plain = torte.scene()
plain:add(torte.shape.mesh{file = "quads.obj", material = torte.material.matte{color = 0.5}})
plain:add(torte.light.infinite{radiance = 1})
local img2 = render(plain)
assert(math.abs(img2:pixel(11, 4) - img2:pixel(4, 4)) < 0.1, "one material for both quads")
print("ok")
)");
  const Result r = run(dir, {"--quiet", script});
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
  CHECK(r.err.find("warning") == std::string::npos);
}

TEST_CASE("obj mtl lua: missing MTL files, unknown materials and textures are warnings", "[obj_mtl]") {
  ObjDir dir("warnings");
  dir.write("a.obj", "mtllib gone.mtl\nmtllib ok.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nowhere\nf 1 2 3\n"
                     "usemtl textured\nf 1 3 2\n");
  dir.write("ok.mtl", "newmtl textured\nKd 0.5 0.5 0.5\nmap_Kd missing.png\nPbr_whatever 1\n");
  const std::string script = dir.write("scene.lua",
                                       "local s = torte.shape.mesh{file = 'a.obj'}\nassert(#s == 2)\nprint('ok')\n");
  const Result r = run(dir, {"--quiet", script});
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
  using Catch::Contains;
  CHECK_THAT(r.err, Contains("warning: a.obj: line 1: material library"));
  CHECK_THAT(r.err, Contains("gone.mtl"));
  CHECK_THAT(r.err, Contains("a.obj: line 6: material 'nowhere' is not defined"));
  CHECK_THAT(r.err, Contains("ok.mtl: line 4: unknown MTL statement 'Pbr_whatever' ignored"));
  CHECK_THAT(r.err, Contains("material 'textured': cannot open image texture 'missing.png'"));
  CHECK_THAT(r.err, Contains("(the map is ignored)"));
}

TEST_CASE("obj mtl lua: damaged MTL files are one-line errors", "[obj_mtl]") {
  ObjDir dir("damaged");
  struct Case { const char* mtl; const char* expect; };
  const Case cases[] = {
      {"newmtl a\nKd 0.5 zero 0.5\n", "bad.mtl: line 2: 'zero' is not a number"},
      {"Kd 0.5 0.5 0.5\n", "bad.mtl: line 1: Kd before any newmtl"},
      {"newmtl a\nNs\n", "bad.mtl: line 2: Ns needs a number"},
      {"newmtl a\nd 2\n", "bad.mtl: line 2: d must be in [0, 1]"},
      {"newmtl a\nKe -1 0 0\n", "bad.mtl: line 2: Ke must be finite and non-negative"},
      {"newmtl a\nmap_Bump -bm\n", "bad.mtl: line 2: map_Bump needs a file name"},
  };
  dir.write("m.obj", "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  for (const Case& c : cases) {
    INFO(c.mtl);
    dir.write("bad.mtl", c.mtl);
    const std::string script = dir.write("bad.lua", "-- line 1\nlocal s = torte.shape.mesh{file = 'm.obj'}\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":2:"));
    CHECK_THAT(line, Catch::Contains(c.expect));
  }
}

TEST_CASE("obj mtl lua: the real cornell_box.obj has its light and renders lit", "[obj_mtl]") {
  const std::string obj = std::string(TORTE_SOURCE_DIR) + "/../shared/data/meshes/cornell-box/cornell_box.obj";
  if (!fs::exists(obj)) {
    WARN("skipped: " << obj << " is absent (shared test data not installed)");
    return;
  }
  ObjDir dir("cornell");
  const std::string script = dir.write("scene.lua", R"(
local scene = torte.scene()
scene:add(torte.shape.mesh{file = ")" + obj + R"("})
local camera = torte.camera.perspective{eye = {278, 273, -800}, look_at = {278, 273, 0}, fov = 39}
local img = torte.render{scene = scene, camera = camera, width = 16, height = 16, spp = 16}
local sum = 0
for y = 0, 15 do for x = 0, 15 do sum = sum + img:pixel(x, y) end end
print(("mean %.3f"):format(sum / 256))
assert(sum / 256 > 0.05, "the box is lit")
)");
  const Result r = run(dir, {script}, 120);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("mean "));
  CHECK(r.err.find("; 0 lights") == std::string::npos);
  CHECK(r.err.find("warning") == std::string::npos);
}

TEST_CASE("obj mtl lua: textures, bump maps and mesh:fit", "[obj_mtl]") {
  ObjDir dir("fit");
  dir.write("t.obj", "mtllib t.mtl\nv 0 0 0\nv 4 0 0\nv 4 2 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                     "usemtl tex\nf 1/1 2/2 3/3 4/4\n");
  dir.write("t.mtl", "newmtl tex\nKd 0.3 0.3 0.3\nmap_Kd half.ppm\nmap_Bump -bm 0.01 half.ppm\n");
  dir.write("half.ppm", "P3\n2 1\n255\n0 0 0 255 255 255\n");  // u < 0.5 black, u > 0.5 white
  const std::string script = dir.write("scene.lua", R"(
local scene = torte.scene()
scene:add(torte.shape.mesh{file = "t.obj"})
scene:add(torte.light.infinite{radiance = 1})
local camera = torte.camera.perspective{eye = {2, 1, -5}, look_at = {2, 1, 0}, fov = 20}
local img = torte.render{scene = scene, camera = camera, width = 16, height = 8, spp = 16}
-- World x > 2 (u > 0.5, white texels) is on the image's left; the map replaces Kd 0.3.
local white, black = img:pixel(3, 4), img:pixel(12, 4)
assert(white > 0.8 and white < 1.1 and black < 0.05, "texture: " .. white .. " " .. black)
local mesh, mats = torte.mesh.load("t.obj")
assert(mats.tex.mesh.has_uvs)
-- fit: 1 tall standing at {1, 0, 2}: x spans 2 (4 / 2), y [0, 1]
local T = mesh:fit{height = 1, center = {1, 0, 2}, floor = true}
local p = T:point{0, 0, 0}
assert(math.abs(p[1] - 0) < 1e-6 and math.abs(p[2] - 0) < 1e-6 and math.abs(p[3] - 2) < 1e-6, table.concat(p, " "))
local q = T:point{4, 2, 0}
assert(math.abs(q[1] - 2) < 1e-6 and math.abs(q[2] - 1) < 1e-6, table.concat(q, " "))
local c = mesh:fit{size = 2}:point{2, 1, 0}
assert(math.abs(c[1]) < 1e-6 and math.abs(c[2]) < 1e-6, "centred")
local w = mesh:fit{width = 8}:point{4, 0, 0}
assert(math.abs(w[1] - 4) < 1e-6, "width 8 scales x (the larger of x and z) by 2 about the centre: " .. w[1])
assert((torte.translate(1, 0, 0) * T):point{0, 0, 0}[1] == 1, "fit composes")
for _, bad in ipairs{function() return mesh:fit{height = 1, width = 1} end,
                     function() return mesh:fit{height = -1} end,
                     function() return mesh:fit{size = 1, centre = {0, 0, 0}} end} do
  assert(not pcall(bad))
end
local ok, msg = pcall(function() return mesh:fit{height = 1, width = 1} end)
assert(msg:find("cannot be combined", 1, true), msg)
ok, msg = pcall(function() return torte.mesh.load("t.obj"):fit{size = 1, depth = 1} end)
assert(msg:find("'depth'", 1, true), msg)
print("ok")
)");
  const Result r = run(dir, {"--quiet", script});
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
  CHECK(r.err.find("warning") == std::string::npos);
}
