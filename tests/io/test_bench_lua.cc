// torte.bench from Lua (lua/bind_bench.cc): every kernel on every ray kind and every SIMD target the CPU runs
// agrees with the scalar reference on a scene of triangles, quadrics, a voxel grid and instances; counts are
// deterministic; the script's SIMD target survives the call; bad keys are one-line errors.
#include <catch2/catch.hpp>
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/memory_budget.h"
#include "runtime.h"
#include "test_support.h"
#include "types.h"

namespace torte {
namespace {

struct BenchState {
  lua_State* L = luaL_newstate();
  lua::RunContext ctx;
  BenchState() {
    luaL_openlibs(L);
    ctx.quiet = true;
    lua::set_run_context(L, &ctx);
    lua::open_torte_module(L, lua::RunOptions{});
  }
  ~BenchState() { lua_close(L); }
  std::string run(const std::string& code) {  // "" or the error
    if (luaL_dostring(L, code.c_str()) == LUA_OK) return "";
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "?";
    lua_pop(L, 1);
    return msg;
  }
};

const char kScene[] = R"(
local M = torte.material.matte{color = 0.5}
scene = torte.scene()
scene:add(torte.shape.cube{transform = torte.translate(0, 1, 0) * torte.scale(3, 1, 3), material = M})
scene:add(torte.shape.sphere{radius = 0.4, transform = torte.translate(-0.8, 0.4, 0), material = M})
scene:add(torte.shape.polygon{points = {{-0.3, 1.95, -0.3}, {0.3, 1.95, -0.3}, {0.3, 1.95, 0.3}, {-0.3, 1.95, 0.3}},
                              emission = 5, material = M})
local g = torte.voxel.grid()
for x = 0, 5 do for z = 0, 5 do if (x + z) % 2 == 0 then g:set(x, 0, z, 1) end end end
scene:add(g:shape{transform = torte.translate(0.2, 0, -0.6) * torte.scale(0.12), material = M})
local group = torte.group()
group:add(torte.shape.cube{transform = torte.scale(0.15), material = M})
for i = 0, 3 do scene:add(torte.instance{group = group, transform = torte.translate(-1.5 + i, 0.15, 1)}) end
camera = torte.camera.perspective{eye = {0, 1, 2.8}, look_at = {0, 0.5, 0}, fov = 60}
)";

TEST_CASE("torte.bench: every kernel, ray kind and SIMD target agrees with the scalar reference", "[bench_lua]") {
  BenchState s;
  REQUIRE(s.run(kScene) == "");
  const std::string check = R"(
local before = torte.simd.current()
local counted = {}
for _, target in ipairs(torte.simd.targets()) do
  for _, rays in ipairs{"camera", "diffuse", "shadow"} do
    for _, kernel in ipairs{"single", "packet8", "packet16"} do
      local r = torte.bench{scene = scene, camera = camera, rays = rays, kernel = kernel, simd = target,
                            width = 48, height = 40, reps = 2}
      local what = ("%s %s %s: "):format(target, rays, kernel)
      assert(r.valid, what .. r.mismatches .. " of " .. r.rays .. " rays disagree with the reference")
      assert(r.simd == target and r.kernel == kernel and r.rays_kind == rays, what .. "labels")
      assert(r.mrays > 0 and r.mrays_min <= r.mrays and r.mrays <= r.mrays_max, what .. "rates")
      -- Inside the closed box every camera and diffuse ray hits; shadow rays are blocked by the sphere, the
      -- voxels and the instances, or not.
      if rays == "shadow" then assert(r.hits > 0 and r.hits < r.rays, what .. "occluded " .. r.hits)
      else assert(r.hits == r.rays, what .. "hits " .. r.hits) end
      -- Closest-hit rays report the work per ray (every one hits something: a node and a primitive at least);
      -- any-hit rays have no counting kernel.
      if rays == "shadow" then assert(r.nodes_per_ray == nil and r.prims_per_ray == nil, what .. "counts")
      else assert(r.nodes_per_ray >= 1 and r.prims_per_ray >= 1, what .. "counts " .. tostring(r.nodes_per_ray)) end
      -- The rays are the same whatever the kernel and target: so are their number, the reference's hits and
      -- the counts (taken on the reference target).
      local key = rays
      if counted[key] then
        assert(counted[key][1] == r.rays and counted[key][2] == r.reference_hits and
               counted[key][3] == r.nodes_per_ray and counted[key][4] == r.prims_per_ray, what .. "ray set changed")
      else
        counted[key] = {r.rays, r.reference_hits, r.nodes_per_ray, r.prims_per_ray}
      end
    end
  end
end
assert(counted.camera[1] == 48 * 40, "one camera ray per pixel")
assert(torte.simd.current() == before, "torte.bench must leave the script's target as it was")
)";
  CHECK(s.run(check) == "");
}

TEST_CASE("torte.bench: bad keys and impossible requests are errors naming the key", "[bench_lua]") {
  BenchState s;
  REQUIRE(s.run(kScene) == "");
  CHECK_THAT(s.run("torte.bench{scene = scene, camera = camera, kernel = 'packet4'}"),
             Catch::Contains("'kernel' must be \"single\", \"packet8\" or \"packet16\""));
  CHECK_THAT(s.run("torte.bench{scene = scene, camera = camera, rays = 'glossy'}"),
             Catch::Contains("'rays' must be \"camera\", \"diffuse\" or \"shadow\""));
  CHECK_THAT(s.run("torte.bench{scene = scene, camera = camera, simd = 'neon'}"), Catch::Contains("neon"));
  CHECK_THAT(s.run("torte.bench{scene = scene, camera = camera, reps = 0}"), Catch::Contains("'reps' must be in"));
  CHECK_THAT(s.run("torte.bench{scene = scene, camera = camera, widht = 3}"), Catch::Contains("unknown key 'widht'"));
  CHECK_THAT(s.run("torte.bench{camera = camera}"), Catch::Contains("'scene' is required"));
  CHECK_THAT(s.run("local e = torte.scene(); e:add(torte.shape.sphere{}); "
                   "torte.bench{scene = e, camera = camera, rays = 'shadow'}"),
             Catch::Contains("\"shadow\" needs a scene with lights"));
  {  // rays that would not fit are refused before they are made
    set_memory_limit(uint64_t(1) << 30);
    CHECK_THAT(s.run("torte.bench{scene = scene, camera = camera, width = 8192, height = 8192}"),
               Catch::Contains("torte.bench: the rays of a 8192x8192 camera"));
    set_memory_limit(0);
  }
  // A failed call leaves the target as it was too.
  CHECK(s.run("assert(torte.simd.current() == torte.simd.targets()[1])") == "");
}

TEST_CASE("torte.bench: kernel = \"embree\" on scenes of triangle meshes, or the error saying it is missing",
          "[bench_lua]") {
  BenchState s;
  // Triangle meshes only: a closed box, a smaller box and a mesh polygon light; an odd image size, so the last
  // groups of 16 are partial; an off-axis camera, so no pixel centre lies exactly on an edge.
  REQUIRE(s.run(R"(
local M = torte.material.matte{color = 0.5}
tris = torte.scene()
tris:add(torte.shape.cube{transform = torte.translate(0, 1, 0) * torte.scale(3, 1, 3), material = M})
tris:add(torte.shape.cube{transform = torte.translate(-0.5, 0.3, 0.1) * torte.rotate(25, {0, 1, 0}) *
                                      torte.scale(0.3), material = M})
tris:add(torte.shape.polygon{points = {{-0.3, 1.95, -0.3}, {0.3, 1.95, -0.3}, {0.3, 1.95, 0.3}, {-0.3, 1.95, 0.3}},
                             emission = 5, material = M})
cam = torte.camera.perspective{eye = {0.13, 1.07, 2.71}, look_at = {0.05, 0.52, 0.03}, fov = 60}
ball = torte.scene():add(torte.shape.sphere{radius = 0.4}, torte.shape.cube{transform = torte.translate(0, -2, 0)})
)") == "");
#ifdef TORTE_HAVE_EMBREE
  const std::string check = R"(
-- Two threads where the machine has them.
local two = pcall(torte.bench, {scene = tris, camera = cam, kernel = "single", width = 8, height = 8, reps = 1,
                                threads = 2})
for _, threads in ipairs(two and {1, 2} or {1}) do
  for _, rays in ipairs{"camera", "diffuse", "shadow"} do
    local r = torte.bench{scene = tris, camera = cam, rays = rays, kernel = "embree", width = 37, height = 29,
                          reps = 2, threads = threads}
    local what = ("embree %s, %d thread(s): "):format(rays, threads)
    assert(r.valid and r.mismatches == 0, what .. r.mismatches .. " of " .. r.rays .. " rays disagree")
    assert(r.kernel == "embree" and r.rays_kind == rays, what .. "labels")
    assert(r.hits == r.reference_hits, what .. r.hits .. " hits, the reference " .. r.reference_hits)
    assert(r.mrays > 0 and r.mrays_min <= r.mrays and r.mrays <= r.mrays_max, what .. "rates")
    if rays == "camera" then assert(r.rays == 37 * 29 and r.hits == r.rays, what .. "every camera ray hits") end
    if rays == "shadow" then assert(r.hits > 0 and r.hits < r.rays, what .. "occluded " .. r.hits) end
    -- The same rays as the torte kernels trace: the same number and reference.
    local t = torte.bench{scene = tris, camera = cam, rays = rays, kernel = "single", width = 37, height = 29, reps = 1}
    assert(t.rays == r.rays and t.reference_hits == r.reference_hits, what .. "ray set differs from torte's")
    assert(t.scene_reused, what .. "the torte scene is reused")
  end
end
-- The Embree scene is built once per torte scene.
local again = torte.bench{scene = tris, camera = cam, kernel = "embree", width = 8, height = 8, reps = 1}
assert(again.scene_reused and again.valid, "Embree scene reused")
)";
  CHECK(s.run(check) == "");
  // Shapes Embree is not given are refused, naming what the scene has.
  CHECK_THAT(s.run("torte.bench{scene = ball, camera = cam, kernel = 'embree', width = 8, height = 8, reps = 1}"),
             Catch::Contains("kernel \"embree\" supports scenes of triangle meshes only (this scene has 1 quadric)"));
  CHECK_THAT(s.run("local g = torte.group(); g:add(torte.shape.cube{}); "
                   "local sc = torte.scene():add(torte.instance{group = g}, torte.instance{group = g}); "
                   "torte.bench{scene = sc, camera = cam, kernel = 'embree', width = 8, height = 8, reps = 1}"),
             Catch::Contains("(this scene has 2 instances)"));
  // The scene that was refused did not spoil the next call.
  CHECK(s.run("assert(torte.bench{scene = tris, camera = cam, kernel = 'embree', width = 8, height = 8, "
              "reps = 1}.valid)") == "");
#else
  CHECK_THAT(s.run("torte.bench{scene = tris, camera = cam, kernel = 'embree', width = 8, height = 8, reps = 1}"),
             Catch::Contains("kernel \"embree\" is not available: torte was built without Embree"));
#endif
}

}  // namespace
}  // namespace torte

// The shipped benchmark scripts at a tiny size, as users run them and under --sandbox: every row valid. They
// need ../shared/data (the bunny, a Minecraft world) and say so when it is absent.
TEST_CASE("torte.bench: scenes/bench-*.lua print a table of valid rows", "[bench_lua][scenes]") {
  torte::test::TempDir dir("bench_lua", "scenes");
  const std::string data = std::string(TORTE_SOURCE_DIR) + "/../shared/data";
  struct Case {
    const char* scene;
    std::vector<std::string> args;
    const char* needs;
  };
  const Case cases[] = {
      {"scenes/bench-traversal.lua", {"width=24", "height=16", "reps=1"}, "/meshes/bunny/bun_zipper.ply"},
      {"scenes/bench-minecraft.lua", {"width=24", "height=16", "reps=1", "box=0,60,0,16,80,16"},
       "/minecraft/bluenbt-1.20.1-paper"},
  };
  for (const Case& c : cases) {
    if (!std::filesystem::exists(data + c.needs)) {
      WARN(c.scene << ": skipped, " << data + c.needs << " is missing");
      continue;
    }
    for (bool sandbox : {false, true}) {
      INFO(c.scene << (sandbox ? " under --sandbox" : ""));
      std::vector<std::string> args{"--quiet"};
      if (sandbox) args.insert(args.end(), {"--sandbox", "--allow-read", "../shared/data"});
      args.push_back(c.scene);
      args.insert(args.end(), c.args.begin(), c.args.end());
      const torte::test::Result r = torte::test::run_torte(dir, args, 300, TORTE_SOURCE_DIR);
      INFO("stdout: " << r.out << "\nstderr: " << r.err);
      REQUIRE(r.code == 0);
      int rows = 0;
      for (const std::string& line : torte::test::lines_of(r.out)) {
        if (!(line.starts_with("camera") || line.starts_with("diffuse") || line.starts_with("shadow"))) continue;
        ++rows;
        CHECK(line.ends_with("yes"));
      }
      CHECK(rows == 9);  // 3 ray kinds x 3 kernels
      CHECK_THAT(r.out, Catch::Contains("best/scalar"));
    }
  }
}
