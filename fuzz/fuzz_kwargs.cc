// The keyword-table checker (lua/binding.h KwArgs) through the real bindings: one constructor that takes a
// keyword table (torte.material.*, shape.*, light.*, camera.*, filter.*, texture.*, instance, voxel.grid,
// mesh:subdivide, grid:define, grid:shape, torte.render) called with a fuzzed table. Promises checked: a call
// that returns has no key outside torte_keywords() and no positional entry (typos never pass silently); what it
// returns renders in a tiny scene without a crash.
#include <lauxlib.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "error_checks.h"
#include "harness.h"
#include "lua_values.h"

namespace {

using torte::fuzz::FuzzInput;
using torte::fuzz::FuzzLua;
using torte::fuzz::LuaValueMaker;

// Calls the constructor with the table on top of the stack; the result, placed in a scene, is rendered at 4x4.
const char kDriver[] = R"lua(
local T = torte
local fns, fn_names = {}, {}
local function add(name, f) fns[#fns + 1] = f; fn_names[#fns] = name end
for _, sub in ipairs{"material", "shape", "light", "camera", "filter", "texture"} do
  local names = {}
  for name in pairs(T[sub]) do names[#names + 1] = name end
  table.sort(names)
  for _, name in ipairs(names) do add("torte." .. sub .. "." .. name, T[sub][name]) end
end
add("torte.instance", T.instance)
add("torte.voxel.grid", T.voxel.grid)
local mesh = T.mesh.load("fx.ply")
add("mesh:subdivide", function(kw) return mesh:subdivide(kw) end)
add("grid:define", function(kw) local g = T.voxel.grid{}; g:set(0, 0, 0, 1); g:define(kw); return g:shape{} end)
add("grid:shape", function(kw) local g = T.voxel.grid{}; g:set(0, 0, 0, 2); return g:shape(kw) end)
add("torte.render", function(kw)
  kw.scene = kw.scene or T.scene()
  kw.camera = kw.camera or T.camera.perspective{}
  -- torte's default image size and spp are legitimate but take seconds: tiny ones unless the input gave some
  if kw.width == nil then kw.width = 4 end
  if kw.height == nil then kw.height = 4 end
  if kw.spp == nil then kw.spp = 1 end
  return T.render(kw)
end)
local tname = {}
local function type_of(v)
  local mt = getmetatable(v)
  return type(mt) == "string" and mt or type(v)
end
local function render(object)
  local kind = type_of(object)
  local scene, camera, filter = T.scene(), T.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}}, nil
  scene:add(T.light.point{position = {0, 2, -2}, intensity = 10})
  if kind == "torte.material" then
    scene:add(T.shape.sphere{material = object})
  elseif kind == "torte.texture" then
    scene:add(T.shape.sphere{material = T.material.matte{color = object}})
  elseif kind == "torte.shape" or kind == "torte.light" or kind == "torte.instance" then
    scene:add(object)
    scene:add(T.shape.cube{})
  elseif kind == "torte.camera" then
    camera = object
    scene:add(T.shape.sphere{})
  elseif kind == "torte.filter" then
    filter = object
    scene:add(T.shape.sphere{})
  elseif kind == "torte.mesh" then
    if object.triangles > 20000 then return end
    scene:add(T.shape.mesh{mesh = object})
  else
    return
  end
  T.render{scene = scene, camera = camera, filter = filter, width = 4, height = 4, spp = 1, max_depth = 4}
end
-- For TORTE_FUZZ_VERBOSE: the call about to be made.
local function describe(i, kw)
  local keys = {}
  for k, v in pairs(kw) do keys[#keys + 1] = ("%s = %s"):format(tostring(k), tostring(v)) end
  table.sort(keys)
  return fn_names[i] .. "{" .. table.concat(keys, ", ") .. "}"
end
return {fns = fns, render = render, describe = describe}
)lua";

struct State {
  std::unique_ptr<FuzzLua> lua;
  int functions = 0;
};
State* g_state = nullptr;

struct Call {
  FuzzInput* in;
  bool only_known = true;
  bool returned = false;
};

int run_one(lua_State* L) {
  auto* call = static_cast<Call*>(lua_touserdata(L, 1));
  lua_getfield(L, LUA_REGISTRYINDEX, "torte.fuzz.kwargs");
  const int driver = lua_gettop(L);
  lua_getfield(L, driver, "fns");
  const lua_Integer index = lua_Integer(1 + call->in->pick(g_state->functions));
  lua_rawgeti(L, -1, index);
  LuaValueMaker maker(L, *call->in);
  maker.push_kwargs(0, &call->only_known);
  if (torte::fuzz::verbose()) {
    lua_getfield(L, driver, "describe");
    lua_pushinteger(L, index);
    lua_pushvalue(L, -3);
    lua_call(L, 2, 1);
    std::fprintf(stderr, "fuzz: calling %s\n", lua_tostring(L, -1));
    lua_pop(L, 1);
  }
  lua_call(L, 1, 1);
  call->returned = true;
  if (torte::fuzz::verbose()) std::fprintf(stderr, "fuzz: the call returned a %s\n", luaL_typename(L, -1));
  // Render what came back (a failing render is an error like any other: it must just not crash).
  lua_getfield(L, driver, "render");
  lua_insert(L, -2);
  lua_call(L, 1, 0);
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torte::fuzz::init_process();
  if (chdir(torte::fuzz::scratch_dir().c_str()) != 0) return 1;
  torte::fuzz::write_fixtures();
  g_state = new State;
  g_state->lua = std::make_unique<FuzzLua>();
  torte::fuzz::install_value_pools(*g_state->lua);
  lua_State* L = g_state->lua->state();
  std::string error;
  if (!g_state->lua->run(kDriver, &error)) torte::fuzz::broken_promise("kwargs driver: " + error);
  lua_getfield(L, -1, "fns");
  g_state->functions = int(lua_rawlen(L, -1));
  lua_pop(L, 1);
  lua_setfield(L, LUA_REGISTRYINDEX, "torte.fuzz.kwargs");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzInput in(data, size);
  Call call{&in};
  g_state->lua->set_instruction_budget(2'000'000);
  g_state->lua->call(run_one, &call);
  if (call.returned && !call.only_known)
    torte::fuzz::broken_promise("a binding accepted a keyword table with a positional entry or an unknown key");
  lua_State* L = g_state->lua->state();
  lua_settop(L, 0);
  lua_gc(L, LUA_GCCOLLECT);
  torte::fuzz::remove_non_fixtures();
  return 0;
}
