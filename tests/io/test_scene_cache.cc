// torte.render{} reuses the flattened scene and its BVHs while the scene is unchanged (lua/scene_cache.h): a new
// camera, spp, size or integrator rebuilds nothing, any change of the scene or of a group it places rebuilds, and
// a reused scene renders exactly the image a fresh build does.
#include <catch2/catch.hpp>

#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "runtime.h"
#include "scene_cache.h"
#include "test_support.h"
#include "types.h"

using namespace torte;
using namespace torte::test;

namespace {

// The torte module in a fresh state; renders are quiet.
struct CacheState {
  lua_State* L = luaL_newstate();
  lua::RunContext ctx;
  CacheState() {
    luaL_openlibs(L);
    ctx.quiet = true;
    lua::set_run_context(L, &ctx);
    lua::open_torte_module(L, lua::RunOptions{});
  }
  ~CacheState() { lua_close(L); }
  // Runs `code`; returns "" when it succeeds, else the error message.
  std::string run(const std::string& code) {
    if (luaL_dostring(L, code.c_str()) == LUA_OK) return "";
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "?";
    lua_pop(L, 1);
    return msg;
  }
};

// A room of boxes and spheres under a point light and a dim sky; `same` compares two images pixel for pixel.
const char kPrelude[] = R"(
local M = torte.material
function make_scene()
  local s = torte.scene()
  s:add(torte.shape.cube{transform = torte.translate(0, -1.5, 0) * torte.scale(4, 0.5, 4),
                         material = M.matte{color = {0.7, 0.7, 0.7}}})
  s:add(torte.shape.sphere{radius = 0.6, transform = torte.translate(-0.7, -0.4, 0.3),
                           material = M.plastic{color = {0.8, 0.2, 0.1}}})
  s:add(torte.light.point{position = {1, 2.5, -2}, intensity = 30})
  s:add(torte.light.infinite{radiance = {0.1, 0.1, 0.15}})
  return s
end
cameras = {
  torte.camera.perspective{eye = {0, 0.5, -5}, look_at = {0, -0.5, 0}, fov = 40},
  torte.camera.perspective{eye = {4, 1, -3}, look_at = {0, -0.5, 0}, fov = 35},
  torte.camera.perspective{eye = {-4, 2, -2}, look_at = {0, -0.5, 0}, fov = 45},
  torte.camera.orthographic{eye = {0, 5, -0.1}, look_at = {0, 0, 0}, extent = 5},
}
function shot(scene, i, extra)
  local args = {scene = scene, camera = cameras[i], width = 20, height = 14, spp = 2, seed = 5}
  for k, v in pairs(extra or {}) do args[k] = v end
  return torte.render(args)
end
function same(a, b)
  if a.width ~= b.width or a.height ~= b.height then return false end
  for y = 0, a.height - 1 do
    for x = 0, a.width - 1 do
      local r1, g1, b1 = a:pixel(x, y)
      local r2, g2, b2 = b:pixel(x, y)
      if r1 ~= r2 or g1 ~= g2 or b1 ~= b2 then return false end
    end
  end
  return true
end
)";

// Runs kPrelude, then `code`, in a fresh state: "" when both succeed, else the error message.
std::string run_after_prelude(const char* code) {
  CacheState st;
  const std::string prelude = st.run(kPrelude);
  return prelude.empty() ? st.run(code) : "kPrelude: " + prelude;
}

// A quadric unit sphere at the origin.
ShapeDesc unit_sphere() {
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Quadric;
  s.quadric.kind = QuadricKind::Sphere;
  s.quadric.radius = 1;
  return s;
}

}  // namespace

TEST_CASE("scene cache: four cameras on one scene build it once, each image equal to a fresh build's",
          "[lua][scene_cache]") {
  CHECK(run_after_prelude(R"(
local s = make_scene()
local imgs = {}
for i = 1, 4 do imgs[i] = shot(s, i) end
assert(not imgs[1].scene_reused, "the first render builds")
for i = 2, 4 do assert(imgs[i].scene_reused, "render " .. i .. " rebuilt an unchanged scene") end
assert(not same(imgs[1], imgs[2]), "the cameras differ")
for i = 2, 4 do
  local fresh = shot(make_scene(), i)
  assert(not fresh.scene_reused, "a new scene object is built")
  assert(same(imgs[i], fresh), "render " .. i .. " of the reused scene differs from a fresh build's")
end
)") == "");
}

TEST_CASE("scene cache: spp, size, integrator, seed and filter changes reuse the scene", "[lua][scene_cache]") {
  CHECK(run_after_prelude(R"(
local s = make_scene()
assert(not shot(s, 1).scene_reused)
for _, extra in ipairs{{spp = 3}, {width = 9, height = 31}, {integrator = "direct"}, {integrator = "igi"},
                       {seed = 9}, {max_depth = 2}, {filter = torte.filter.gaussian{}}} do
  assert(shot(s, 2, extra).scene_reused, "a settings change rebuilt the scene")
end
)") == "");
}

TEST_CASE("scene cache: every change of the scene rebuilds it and renders the changed scene", "[lua][scene_cache]") {
  // Each step changes the scene in another way after it was rendered; the render that follows must rebuild and
  // give exactly the image of the changed scene built afresh (the same steps applied to a new scene).
  CHECK(run_after_prelude(R"(
local steps = {
  function(w) w.s:add(torte.shape.sphere{radius = 0.5, transform = torte.translate(0.8, -0.5, -0.5)}) end,
  function(w) w.s:add(torte.light.point{position = {-2, 2, -2}, intensity = 15}) end,
  function(w)  -- a group placed in the scene
    w.g = torte.group()
    w.g:add(torte.shape.cube{transform = torte.scale(0.3, 0.3, 0.3)})
    w.s:add(torte.instance{group = w.g, transform = torte.translate(0.9, -0.7, 0.6)})
  end,
  function(w) w.g:add(torte.shape.sphere{radius = 0.25, transform = torte.translate(0, 0.6, 0)}) end,  -- the group grows
  function(w)  -- a frame, filled later through a nested group
    w.f = w.s:frame(torte.translate(-1.2, -0.8, -1), function(f) f:add(torte.shape.sphere{radius = 0.3}) end)
  end,
  function(w)
    w.inner = torte.group()
    w.inner:add(torte.shape.sphere{radius = 0.15, transform = torte.translate(0.4, 0, 0)})
    w.f:add(torte.instance{group = w.inner, transform = torte.translate(0, 0.5, 0)})
  end,
  function(w) w.inner:add(torte.shape.cube{transform = torte.scale(0.2, 0.2, 0.2)}) end,  -- two levels down
  function(w)  -- a voxel grid whose cell shape is a group
    w.cell = torte.group()
    w.cell:add(torte.shape.sphere{radius = 0.3, transform = torte.translate(0.5, 0.5, 0.5)})
    local grid = torte.voxel.grid{}
    grid:set(0, 0, 0, -3)
    grid:set(1, 0, 0, -3)
    grid:define{id = -3, shape = w.cell}
    w.s:add(grid:shape{transform = torte.translate(0, -1, -1.5) * torte.scale(0.8, 0.8, 0.8)})
  end,
  function(w) w.cell:add(torte.shape.cube{transform = torte.translate(0.5, 0.1, 0.5) * torte.scale(0.4, 0.1, 0.4)}) end,
}
local function built(n)
  local w = {s = make_scene()}
  for k = 1, n do steps[k](w) end
  return w
end
local w = built(0)
local before = shot(w.s, 1)
for k = 1, #steps do
  steps[k](w)
  local img = shot(w.s, 1)
  assert(not img.scene_reused, "step " .. k .. ": the changed scene was not rebuilt")
  assert(not same(img, before), "step " .. k .. ": the change is not in the image")
  assert(same(img, shot(built(k).s, 1)), "step " .. k .. ": the image differs from a fresh build of the scene")
  before = shot(w.s, 1)  -- built again: the cache held the fresh copy
  assert(not before.scene_reused and same(before, img), "step " .. k .. ": rebuilding gave another image")
  assert(shot(w.s, 2).scene_reused, "step " .. k .. ": an unchanged scene was rebuilt")
end
)") == "");
}

TEST_CASE("scene cache: the old scene is released before the new one is built, and a failed build leaves none",
          "[scene_cache]") {
  SceneBuilder b;
  const ShapeDesc sphere = unit_sphere();
  b.add_shape(sphere);
  lua::SceneCache cache;
  int builds = 0;
  auto build = [&] {
    ++builds;
    return b.flatten();
  };
  const std::weak_ptr<const Scene> first = cache.get(b, build).scene;
  CHECK(cache.get(b, build).reused);
  CHECK(builds == 1);
  b.add_shape(sphere);
  bool released = false;
  const auto second = cache.get(b, [&] {
    released = first.expired();  // nothing else holds the first scene, so the cache must have let it go
    return build();
  });
  CHECK(released);
  CHECK_FALSE(second.reused);
  CHECK(second.scene->quadrics.size() == 2);
  // A build that throws (here: a group that contains itself, which flatten refuses; the fingerprint walk ends
  // on the cycle) leaves the cache empty, not holding the previous scene.
  auto loop = std::make_shared<SceneBuilder>();
  loop->add_shape(sphere);
  loop->add_instance({loop, Transform()});
  SceneBuilder with_loop;
  with_loop.add_instance({loop, Transform()});
  CHECK(with_loop.fingerprint().size() == 2);
  CHECK(second.scene.use_count() == 2);  // here and in the cache
  CHECK_THROWS_WITH(cache.get(with_loop, [&] { return with_loop.flatten(); }), Catch::Contains("nest more than"));
  CHECK(second.scene.use_count() == 1);
  builds = 0;
  CHECK_FALSE(cache.get(b, build).reused);
  CHECK(builds == 1);
  *loop = SceneBuilder();  // breaks the cycle, so the test does not leak it
}

TEST_CASE("scene cache: fingerprints follow changes, copies and moves of builders", "[scene_cache]") {
  auto group = std::make_shared<SceneBuilder>();
  SceneBuilder scene;
  scene.add_instance({group, Transform()});
  const auto f0 = scene.fingerprint();
  CHECK(f0.size() == 2);  // the scene and its group
  CHECK(scene.fingerprint() == f0);
  group->add_shape(unit_sphere());
  const auto f1 = scene.fingerprint();
  CHECK(f1 != f0);
  SceneBuilder copy = scene;  // same content: the same fingerprint is right
  CHECK(copy.fingerprint() == f1);
  copy.add_light(Light{});
  CHECK(copy.fingerprint() != f1);
  CHECK(scene.fingerprint() == f1);
  SceneBuilder moved = std::move(scene);
  CHECK(moved.fingerprint() == f1);
  CHECK(scene.fingerprint() != f1);  // emptied, so it must not pass for what it held
  CHECK(scene.fingerprint().size() == 1);
}

TEST_CASE("scene cache: the render summary shows the reused scene's build time", "[cli][scene_cache]") {
  TempDir dir("scene_cache", "summary");
  const std::string script = dir.write("turntable.lua", std::string(kPrelude) + R"(
local s = make_scene()
for i = 1, 4 do shot(s, i) end
)");
  const Result r = run_torte(dir, {script}, 60);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  REQUIRE(r.code == 0);
  const std::regex summary(R"(render 20x14, 2 spp: build (.+?), render \d)");
  std::vector<std::string> builds;
  for (std::sregex_iterator it(r.err.begin(), r.err.end(), summary), end; it != end; ++it)
    builds.push_back((*it)[1]);
  REQUIRE(builds.size() == 4);
  CHECK_THAT(builds[0], !Catch::Contains("reused"));
  for (size_t i = 1; i < 4; ++i) CHECK_THAT(builds[i], Catch::Matches(R"(\d+\.\d\d ms \(scene unchanged, reused\))"));
}
