// The Lua API driven by fuzzed call sequences. Each input decodes into up to 48 operations on a fresh Lua state
// set up as lua/runtime.cc does: calls of torte.* functions with fuzzed arguments (lua_values.h), method calls
// and field reads on objects made earlier (16 result slots), arithmetic and concatenation between them, scenes
// filled and rendered at tiny sizes, images written into the scratch directory. Every operation runs protected;
// errors are expected, crashes, hangs, sanitizer reports and memory blow-ups are not. Work per input is bounded:
// a Lua instruction budget, a cap on Lua's memory, torte's memory budget, and size-like values that are either
// small or absurd.
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

constexpr int kSlots = 16;
constexpr int kMaxOps = 48;

// Functions, methods and operators the sequences choose from (the function list is read from the torte table).
const char kSetup[] = R"lua(
local T = torte
local skip = {clock = true, render = true, save = true}
local names, fns = {}, {}
local function walk(t, prefix)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys)
  for _, k in ipairs(keys) do
    local v = t[k]
    if type(v) == "table" and prefix == "" and k ~= "args" then walk(v, k .. ".")
    elseif type(v) == "function" and not skip[k] then names[#names + 1] = prefix .. k; fns[#fns + 1] = v end
  end
end
walk(T, "")
local ops = {
  function(a, b) return a * b end, function(a, b) return a + b end, function(a, b) return a - b end,
  function(a, b) return a / b end, function(a, b) return a .. b end, function(a) return -a end,
  function(a) return #a end, function(a) return tostring(a) end, function(a, b) return a == b end,
  function(a, b) return a < b end, function(a, b) return a[b] end, function(a, b) return a % b end,
  function(a, b) return a ^ b end, function(a, b) return a // b end, function(a) return type(a) end,
}
local slots = {
  T.scene(), T.camera.perspective{eye = {0, 1, -4}, look_at = {0, 0, 0}}, T.material.matte{}, T.identity(),
  T.texture.checker{}, T.mesh.load("fx.ply"), T.voxel.grid{}, T.group(),
}
return {fns = fns, names = names, ops = ops, slots = slots}
)lua";

const char* const kMethods[] = {"add", "frame", "subdivide", "smooth_normals", "bounds", "write", "pixel", "mean",
                                "set", "get", "set_chunk", "count", "chunks", "define", "build", "shape", "save",
                                "table", "unpack_bits", "inverse", "point", "eval"};
const char* const kFields[] = {"triangles", "vertices", "has_normals", "has_uvs", "width", "height", "rays",
                               "dropped_samples", "render_seconds", "interrupted", "type", "input", "kind", "n",
                               "nope", "__index", "__gc"};
const char* const kWritePaths[] = {"out.png", "out.exr", "out.hdr", "out.jpg", "out.tif", "out.ppm", "out",
                                   "out.xyz", "fx.dir", "", "sub/dir/out.png", "out.PNG", "out.bmp", "out.tga"};

struct Sequence {
  FuzzInput* in;
  int functions = 0;
};

void push_field(lua_State* L, int table, const char* key) { lua_getfield(L, table, key); }

// One operation; its result (if any) is left on top and stored in a slot by the caller.
int run_op(lua_State* L) {
  auto* seq = static_cast<Sequence*>(lua_touserdata(L, 1));
  FuzzInput& in = *seq->in;
  lua_getfield(L, LUA_REGISTRYINDEX, "torte.fuzz.api");
  const int api = lua_gettop(L);
  lua_getfield(L, api, "slots");
  const int slots = lua_gettop(L);
  LuaValueMaker make(L, in, slots);
  const uint8_t op = in.byte() % 14;
  const int base = lua_gettop(L);
  auto first_arg = [&] {
    if (in.byte() % 5 < 3) make.push_kwargs(0);
    else make.push_value();
  };
  switch (op) {
    case 0:
    case 1:
    case 2:
    case 3: {  // torte.<function>(args)
      push_field(L, api, "fns");
      const lua_Integer index = lua_Integer(1 + in.pick(size_t(seq->functions)));
      lua_rawgeti(L, -1, index);
      const int nargs = in.byte() % 4;
      if (nargs > 0) first_arg();
      for (int i = 1; i < nargs; ++i) make.push_value();
      if (torte::fuzz::verbose()) {
        push_field(L, api, "names");
        lua_rawgeti(L, -1, index);
        std::string call = std::string(lua_tostring(L, -1)) + "(";
        lua_pop(L, 2);
        for (int i = 0; i < nargs; ++i) call += (i ? ", " : "") + torte::fuzz::describe(L, -nargs + i);
        std::fprintf(stderr, "fuzz: torte.%s)\n", call.c_str());
      }
      lua_call(L, nargs, 1);
      break;
    }
    case 4:
    case 5: {  // slot:method(args)
      lua_rawgeti(L, slots, 1 + in.byte() % kSlots);
      const int self = lua_gettop(L);
      const char* method = kMethods[in.pick(std::size(kMethods))];
      lua_getfield(L, self, method);
      lua_pushvalue(L, self);
      int nargs = 1;
      if (std::string_view(method) == "write" || std::string_view(method) == "save") {
        lua_pushstring(L, kWritePaths[in.pick(std::size(kWritePaths))]);
        ++nargs;
        if (in.byte() & 1) {
          make.push_kwargs(0);
          ++nargs;
        }
      } else {
        const int extra = in.byte() % 5;
        if (extra > 0) first_arg();
        for (int i = 1; i < extra; ++i) make.push_value();
        nargs += extra;
      }
      lua_call(L, nargs, 1);
      break;
    }
    case 6: {  // slot.field
      lua_rawgeti(L, slots, 1 + in.byte() % kSlots);
      if (in.byte() % 4) lua_pushstring(L, kFields[in.pick(std::size(kFields))]);
      else make.push_value();
      lua_gettable(L, -2);
      break;
    }
    case 7: {  // operators between values
      push_field(L, api, "ops");
      lua_rawgeti(L, -1, lua_Integer(1 + in.pick(lua_rawlen(L, -1))));
      make.push_value();
      make.push_value();
      lua_call(L, 2, 1);
      break;
    }
    case 8:
    case 9: {  // torte.render{...} at a tiny size, on a slot's scene and camera when they are ones
      lua_getglobal(L, "torte");
      lua_getfield(L, -1, "render");
      make.push_kwargs(0);
      const int kw = lua_gettop(L);
      lua_rawgeti(L, slots, 1 + in.byte() % kSlots);
      lua_setfield(L, kw, "scene");
      lua_rawgeti(L, slots, 1 + (in.byte() % 2 ? 1 : in.byte() % kSlots));
      lua_setfield(L, kw, "camera");
      for (const char* key : {"width", "height", "spp", "max_depth"}) {
        make.push_number(key);
        lua_setfield(L, kw, key);
      }
      if (in.byte() % 4 == 0) {
        lua_pushstring(L, in.byte() % 2 ? "igi" : "direct");
        lua_setfield(L, kw, "integrator");
      }
      if (torte::fuzz::verbose())
        std::fprintf(stderr, "fuzz: torte.render%s\n", torte::fuzz::describe(L, kw).c_str());
      lua_call(L, 1, 1);
      break;
    }
    case 10: {  // scene:add(object) or scene:frame(transform, callback)
      lua_rawgeti(L, slots, 1 + (in.byte() % 2 ? 0 : in.byte() % kSlots));
      const int scene = lua_gettop(L);
      const bool frame = in.byte() % 3 == 0;
      lua_getfield(L, scene, frame ? "frame" : "add");
      lua_pushvalue(L, scene);
      if (frame) {
        make.push_object();
        make.push_function();
      } else {
        make.push_object();
        make.push_object();
      }
      lua_call(L, 3, 1);
      break;
    }
    case 11: make.push_value(); break;
    case 12: lua_gc(L, LUA_GCCOLLECT); break;
    default: {  // torte.save(image, path)
      lua_getglobal(L, "torte");
      lua_getfield(L, -1, "save");
      lua_rawgeti(L, slots, 1 + in.byte() % kSlots);
      lua_pushstring(L, kWritePaths[in.pick(std::size(kWritePaths))]);
      lua_call(L, 2, 1);
      break;
    }
  }
  // Keep the result (if any) in a slot.
  if (torte::fuzz::verbose())
    std::fprintf(stderr, "fuzz: op %d gave %s\n", op, lua_gettop(L) > base ? luaL_typename(L, -1) : "nothing");
  if (lua_gettop(L) > base) {
    lua_rawseti(L, slots, 1 + in.byte() % kSlots);
  }
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torte::fuzz::init_process();
  if (chdir(torte::fuzz::scratch_dir().c_str()) != 0) return 1;
  torte::fuzz::write_fixtures();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzInput in(data, size);
  {
    FuzzLua lua(size_t(128) << 20);
    torte::fuzz::install_value_pools(lua);
    lua_State* L = lua.state();
    std::string error;
    if (!lua.run(kSetup, &error)) torte::fuzz::broken_promise("lua_api setup: " + error);
    lua_getfield(L, -1, "fns");
    Sequence seq{&in, int(lua_rawlen(L, -1))};
    lua_pop(L, 1);
    lua_setfield(L, LUA_REGISTRYINDEX, "torte.fuzz.api");
    lua.set_instruction_budget(2'000'000);
    for (int i = 0; i < kMaxOps && !in.empty() && !lua.budget_exhausted(); ++i) {
      lua.call(run_op, &seq);
      lua_settop(L, 0);
    }
  }
  torte::fuzz::remove_non_fixtures();
  return 0;
}
