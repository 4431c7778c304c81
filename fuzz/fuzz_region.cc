// The Minecraft region and chunk reader (lua/minecraft/region.lua and world.lua's chunk decoding) driven through
// a Lua state. An input is a region file in short form: byte 0 holds options (bit 0 skip_bad_chunks, bit 1 probes,
// bit 2 emitters, bit 3 a box), byte 1 the number n (mod 9) of header entries, then n 4-byte big-endian location
// words (header entries 0..n-1; the rest of the 8 KiB header is zero), then the file's bytes from offset 8192
// (sector 2) on. The harness writes the full file as r.0.0.mca in the scratch directory and runs
// minecraft.world.load on it, sections going into a voxel grid that is then built. Promise: load succeeds or
// raises a string error that is not a Lua runtime error ("attempt to index a nil value", "bad argument #1 to
// ..."), which would be a bug of the library; with TORTE_FUZZ_STRICT_ERRORS=1 the error must name the file.
#include <lauxlib.h>

#include <cstdio>
#include <memory>
#include <string>

#include "error_checks.h"
#include "fuzz_input.h"
#include "fuzz_support.h"
#include "harness.h"

namespace {

const char kDriver[] = R"lua(
local T = torte
local world = require "minecraft.world"
local blocks = require "minecraft.blocks"
return function(path, options)
  local grid = T.voxel.grid{}
  local opt = {
    files = {path}, registry = blocks.registry(), progress = false,
    skip_bad_chunks = options & 1 ~= 0,
    probes = options & 2 ~= 0 and {{0, 0, 0}, {5, 70, 5}, {-3, -60, 17}} or nil,
    emitters = options & 4 ~= 0,
    box = options & 8 ~= 0 and {0, -64, 0, 24, 320, 24} or nil,
    sink = function(cx, cy, cz, ids) grid:set_chunk(cx, cy, cz, ids) end,
  }
  local ok, stats = pcall(world.load, opt)
  if not ok then
    if type(stats) ~= "string" then error("world.load raised a " .. type(stats), 0) end
    return stats, 0
  end
  if grid:count() > 0 then
    local ok2, err = pcall(function()
      opt.registry:define(grid)
      grid:build()
    end)
    if not ok2 and type(err) ~= "string" then error("building the grid raised a " .. type(err), 0) end
  end
  return nil, stats.sections
end
)lua";

std::unique_ptr<torte::fuzz::FuzzLua> g_lua;
std::string g_path;

struct Args {
  const uint8_t* data;
  size_t size;
};

int run(lua_State* L) {
  auto* a = static_cast<Args*>(lua_touserdata(L, 1));
  torte::fuzz::FuzzInput in(a->data, a->size);
  const uint8_t options = in.byte();
  const int entries = in.byte() % 9;
  std::string file(8192, '\0');
  for (int i = 0; i < entries; ++i)
    for (int k = 0; k < 4; ++k) file[size_t(4 * i + k)] = char(in.byte());
  file += in.rest();
  torte::fuzz::write_file(g_path, file);
  lua_getfield(L, LUA_REGISTRYINDEX, "torte.fuzz.region");
  lua_pushstring(L, g_path.c_str());
  lua_pushinteger(L, options);
  lua_call(L, 2, 2);
  if (torte::fuzz::verbose())
    std::fprintf(stderr, "fuzz: %s (%d sections)\n", lua_isnil(L, -2) ? "loaded" : lua_tostring(L, -2),
                 int(lua_tointeger(L, -1)));
  lua_pop(L, 1);
  if (const char* error = lua_tostring(L, -1)) {
    // A Lua runtime error is a bug of the library: bad data must be reported as what is wrong with it.
    const std::string_view e(error);
    if (e.find("attempt to ") != e.npos || e.find("bad argument #") != e.npos)
      torte::fuzz::broken_promise(std::string("the loader failed with a Lua runtime error: ") + error);
    if (torte::fuzz::strict_errors()) torte::fuzz::check_error_message(error, g_path);
  }
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_lua = std::make_unique<torte::fuzz::FuzzLua>(size_t(256) << 20, /*line_coverage=*/true);
  g_path = torte::fuzz::scratch_path("r.0.0.mca");
  std::string error;
  if (!g_lua->run(kDriver, &error)) torte::fuzz::broken_promise("region driver: " + error);
  lua_setfield(g_lua->state(), LUA_REGISTRYINDEX, "torte.fuzz.region");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Args args{data, size};
  g_lua->set_instruction_budget(20'000'000);
  std::string error;
  if (!g_lua->call(run, &args, &error) && error != "instruction budget exhausted")
    torte::fuzz::broken_promise("region: " + error);
  lua_settop(g_lua->state(), 0);
  lua_gc(g_lua->state(), LUA_GCCOLLECT);
  return 0;
}
