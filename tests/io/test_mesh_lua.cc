// torte.mesh from scripts, end to end through the built binary (TORTE_BINARY): load, subdivide, bounds, placing
// meshes with torte.shape.mesh{mesh=...} / {file=...}, one-line errors naming bad mesh files, and
// scenes/lucy-scale.lua at levels=0.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct MeshDir : TempDir {
  explicit MeshDir(const std::string& name) : TempDir("mesh_lua", name) {}
};

// Runs torte with `args` in `dir` (its working directory, so relative paths resolve there).
Result run(const TempDir& dir, const std::vector<std::string>& args, double timeout = 60) {
  return run_torte(dir, args, timeout, dir.path.string());
}

// A closed octahedron (6 vertices, 8 triangles) as ascii PLY.
const char kOctaPly[] =
    "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 8\nproperty list uchar int vertex_indices\nend_header\n"
    "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
    "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

}  // namespace

TEST_CASE("mesh lua: load, subdivide, bounds and a tiny render", "[mesh_lua]") {
  MeshDir dir("render");
  dir.write("octa.ply", kOctaPly);
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string script = dir.write("scene.lua", R"(
local m = torte.mesh.load("octa.ply")           -- relative to the working directory
assert(m.triangles == 8 and m.vertices == 6, tostring(m))
assert(not m.has_normals and not m.has_uvs)
local s = m:subdivide{levels = 2, displacement = 0.05, seed = 3}
assert(s.triangles == 128 and s.vertices == 66, tostring(s))
local s2 = torte.mesh.subdivide(m, {levels = 2, displacement = 0.05, seed = 3})
local a_lo, a_hi = s:bounds()
local b_lo, b_hi = s2:bounds()
for i = 1, 3 do assert(a_lo[i] == b_lo[i] and a_hi[i] == b_hi[i], "deterministic") end
local lo, hi = m:bounds()
assert(lo[1] == -1 and hi[3] == 1)
assert(torte.mesh.subdivide(m).triangles == 32, "one level by default")
assert(tostring(s):find("128 triangles"))
local t0 = torte.clock()
assert(type(t0) == "number" and torte.clock() >= t0)
local scene = torte.scene()
scene:add(torte.shape.mesh{mesh = s, material = torte.material.matte{color = 0.8}})
scene:add(torte.shape.mesh{file = "tri.obj", transform = torte.translate(0, 0, 3)})
scene:add(torte.light.infinite{radiance = 1})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 40}
-- 64 spp: a single MIS-weighted sample may exceed the albedo, so a 2-spp pixel is too noisy to bound.
local img = torte.render{scene = scene, camera = camera, width = 8, height = 8, spp = 64}
local centre = (img:pixel(3, 3) + img:pixel(4, 3) + img:pixel(3, 4) + img:pixel(4, 4)) / 4
local corner = img:pixel(0, 0)
assert(centre < 0.95 and corner > 0.99, "the mesh is in the middle: " .. centre .. " " .. corner)
print("ok")
)");
  const Result r = run(dir, {"--quiet", script});
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
}

TEST_CASE("mesh lua: bad mesh files and arguments give one-line errors", "[mesh_lua]") {
  MeshDir dir("errors");
  dir.write("octa.ply", kOctaPly);
  std::string cut = kOctaPly;
  dir.write("cut.ply", cut.substr(0, cut.size() - 20));
  dir.write("points.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                          "property float z\nend_header\n0 0 0\n");
  // Each process costs ~0.5 s (OpenImageIO start-up), so only the file errors run as whole scripts.
  struct Case { const char* name; std::string code; std::vector<std::string> expect; };
  const Case cases[] = {
      {"missing load", "local m = torte.mesh.load('missing.ply')",
       {"missing.ply", "cannot open", "torte.mesh.load"}},
      {"missing file=", "local s = torte.shape.mesh{file = 'gone.obj'}", {"gone.obj", "torte.shape.mesh"}},
      {"truncated", "local m = torte.mesh.load('cut.ply')", {"cut.ply", "face 5 of 8: file ends early"}},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string script = dir.write("bad.lua", "-- line 1\n" + c.code + "\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":2:"));
    for (const std::string& e : c.expect) CHECK_THAT(line, Catch::Contains(e));
  }
  // The other errors are caught in one script; each names the script line and the culprit.
  const std::string script = dir.write("pcall.lua", R"(
local function expect(f, ...)
  local ok, message = pcall(f)
  assert(not ok, "no error")
  assert(message:find("pcall.lua:", 1, true), "no location in: " .. message)
  for _, want in ipairs{...} do assert(message:find(want, 1, true), "'" .. want .. "' not in: " .. message) end
end
local octa = torte.mesh.load('octa.ply')
expect(function() return torte.mesh.load('octa.stl') end, "octa.stl", "unknown mesh file type")
expect(function() return torte.shape.mesh{file = 'points.ply'} end, "'file'", "has no triangles")
expect(function() return torte.shape.mesh{mesh = octa, file = 'octa.ply'} end, "'file'", "together with 'mesh'")
expect(function() return torte.shape.mesh{mesh = 3} end, "'mesh'", "torte.mesh", "number")
expect(function() return octa:subdivide{levels = -1} end, "'levels'")
expect(function() return octa:subdivide{level = 2} end, "'level'")
expect(function() return torte.mesh.subdivide(3) end, "expects a torte.mesh")
expect(function() return octa.faces end, "no field 'faces'")
print("ok")
)");
  const Result r = run(dir, {script});
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
}

TEST_CASE("mesh lua: scenes/lucy-scale.lua at levels=0", "[mesh_lua]") {
  const std::string data = std::string(TORTE_SOURCE_DIR) + "/../shared/data/meshes";
  if (!fs::exists(data + "/lucy/lucy_100k.obj")) {
    WARN("skipped: " << data << " is absent (shared test data not installed)");
    return;
  }
  MeshDir dir("lucy");
  const std::string output = dir / "lucy.exr";
  const Result r = run(dir, {"--quiet", std::string(TORTE_SOURCE_DIR) + "/scenes/lucy-scale.lua", "levels=0",
                             "width=16", "height=16", "spp=1", "output=" + output},
                       120);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("lucy-scale: 269421 triangles in all"));
  CHECK(fs::exists(output));
  CHECK(fs::exists(dir / "lucy.png"));
}
