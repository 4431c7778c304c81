// torte.voxel.grid from scripts through the built binary: filling (set, set_chunk with a table and a string),
// id definitions with per-face materials and cell shapes, placement (g:shape, torte.shape.voxels, instancing),
// the build report, and one-line errors naming file and line.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "test_support.h"

using namespace torte::test;

namespace {

struct VoxelDir : TempDir {
  explicit VoxelDir(const std::string& name) : TempDir("voxel_lua", name) {}
};

Result run(const TempDir& dir, const std::vector<std::string>& args, double timeout = 60) {
  return run_torte(dir, args, timeout, dir.path.string());
}

}  // namespace

TEST_CASE("voxel lua: a grid filled from Lua renders with per-id and per-face materials", "[voxel_lua]") {
  VoxelDir dir("render");
  const std::string script = dir.write("grid.lua", R"(
local g = torte.voxel.grid{}
local red = torte.material.matte{color = {0.9, 0.05, 0.05}}
local green = torte.material.matte{color = {0.05, 0.9, 0.05}}
-- a floor 32 x 32 at y = -1 from two chunks per axis: one chunk from a table, the others from strings
local ids = {}
for i = 1, 4096 do ids[i] = (i - 1) // 256 == 15 and 1 or 0 end   -- y = 15 layer
g:set_chunk(-1, -1, -1, ids)
local s = {}
for i = 1, 4096 do s[i] = string.pack("<i2", (i - 1) // 256 == 15 and 1 or 0) end
s = table.concat(s)
g:set_chunk(0, -1, -1, s); g:set_chunk(-1, -1, 0, s); g:set_chunk(0, -1, 0, s)
for x = -2, 1 do for y = 0, 3 do g:set(x, y, 4, 2) end end
g:define{id = 1, material = red, faces = {top = green}}
g:define{id = 2, faces = {side = red, ["-z"] = red, ["+z"] = red, top = red, bottom = red}}
local slab = torte.group()
slab:add(torte.shape.cube{min = {0, 0, 0}, max = {1, 0.5, 1}, material = red})
g:define{id = -1, shape = slab}
g:set(5, 0, 0, -1)
print("count", g:count(), g:chunks(), g:get(0, -1, 0), g:get(-2, 1, 4), g:get(5, 0, 0))
local st = g:build()
print("built", st.voxels, st.bytes <= 8 * st.cells)
local scene = torte.scene()
scene:add(g:shape{})
local grp = torte.group()
grp:add(torte.shape.voxels{grid = g})
scene:add(torte.instance{group = grp, transform = torte.translate(0, 0, 100)})
scene:add(torte.light.infinite{radiance = 1})
local image = torte.render{scene = scene, width = 32, height = 32, spp = 4, integrator = "direct",
  camera = torte.camera.perspective{eye = {0, 12, -20}, look_at = {0, 0, 0}, fov = 40}}
local function mean(x0, y0, x1, y1)
  local r, gg, b, n = 0, 0, 0, 0
  for y = y0, y1 do for x = x0, x1 do local pr, pg, pb = image:pixel(x, y); r, gg, b, n = r + pr, gg + pg, b + pb, n + 1 end end
  return r / n, gg / n
end
local fr, fg = mean(2, 28, 6, 31)     -- floor (green tops)
local wr, wg = mean(14, 8, 17, 11)    -- the wall of id 2 (red)
print(string.format("floor %s wall %s", tostring(fg > 3 * fr), tostring(wr > 3 * wg)))
)");
  const Result r = run(dir, {script});
  check_no_crash(r);
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);
  const auto lines = lines_of(r.out);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0] == "count\t1041\t6\t1\t2\t-1");
  CHECK(lines[1] == "built\t1041\ttrue");
  CHECK(lines[2] == "floor true wall true");
  CHECK_THAT(r.err, Catch::Contains("voxel grid: 1041 voxels in 6 chunks"));
  CHECK_THAT(r.err, Catch::Contains("bytes/voxel"));
}

TEST_CASE("voxel lua: bad arguments are one-line errors naming file and line", "[voxel_lua]") {
  VoxelDir dir("errors");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"local g = torte.voxel.grid{}\ng:define{id = 1, materal = 1}\n", "grid:define: unknown key 'materal'"},
      {"local g = torte.voxel.grid{}\ng:define{id = 1, faces = {tpo = 1}}\n", "unknown key 'tpo'"},
      {"local g = torte.voxel.grid{}\ng:set(0, 0, 0, 40000)\n", "grid:set id must be in [-32768, 32767]"},
      {"local g = torte.voxel.grid{}\ng:set_chunk(0, 0, 0, 'abc')\n", "8192 bytes"},
      {"local g = torte.voxel.grid{}\ng:define{id = 0}\n", "0 is the empty voxel"},
      {"local g = torte.voxel.grid{}\ng:define{id = -2, material = 1}\n", "'shape'"},
      {"local g = torte.voxel.grid{}\nlocal s = torte.shape.voxels{grid = g, transfrom = 1}\n", "unknown key 'transfrom'"},
      {"-- x\nlocal g = torte.voxel.grid{size = 3}\n", "torte.voxel.grid takes no keys (got 'size')"},
  };
  int i = 0;
  for (const auto& [text, expect] : cases) {
    const std::string path = dir.write("bad" + std::to_string(i++) + ".lua", text);
    const std::string line = check_error(run(dir, {"--quiet", path}));
    INFO(line);
    CHECK_THAT(line, Catch::Contains(expect));
    CHECK_THAT(line, Catch::Contains(".lua:2:"));
  }
}
