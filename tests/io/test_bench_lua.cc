// torte.bench from Lua (lua/bind_bench.cc): every kernel on every ray kind and every SIMD target the CPU runs
// agrees with the scalar reference on a scene of triangles, quadrics, a voxel grid and instances; counts are
// deterministic; the script's SIMD target survives the call; bad keys are one-line errors.
#include <catch2/catch.hpp>
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <string>

#include "runtime.h"
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
      -- The rays are the same whatever the kernel and target: so are their number and the reference's hits.
      local key = rays
      if counted[key] then
        assert(counted[key][1] == r.rays and counted[key][2] == r.reference_hits, what .. "ray set changed")
      else
        counted[key] = {r.rays, r.reference_hits}
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
  // A failed call leaves the target as it was too.
  CHECK(s.run("assert(torte.simd.current() == torte.simd.targets()[1])") == "");
}

}  // namespace
}  // namespace torte
