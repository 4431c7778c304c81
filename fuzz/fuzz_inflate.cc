// Decompression through the torte.data bindings: the first byte picks torte.data.inflate (zlib), gunzip, lz4_block
// (the next 2 bytes give the decompressed size) or minecraft.region.lz4_stream (lz4-java's LZ4Block stream, in
// Lua over lz4_block and xxhash32); the rest is the compressed input. Promises: errors name the function (or the
// LZ4 block), lz4_block returns exactly the size asked for.
#include <lauxlib.h>

#include <memory>
#include <string>

#include "error_checks.h"
#include "fuzz_input.h"
#include "fuzz_support.h"
#include "harness.h"

namespace {

const char kDriver[] = R"lua(
local data = torte.data
local region = require "minecraft.region"
local prefixes = {"^torte%.data%.inflate: ", "^torte%.data%.gunzip: ", "^torte%.data%.lz4_block: ", "^LZ4 block %d+ at byte %d+: "}
return function(mode, s, size)
  local ok, out
  if mode == 0 then ok, out = pcall(data.inflate, s)
  elseif mode == 1 then ok, out = pcall(data.gunzip, s)
  elseif mode == 2 then
    ok, out = pcall(data.lz4_block, s, size)
    if ok and #out ~= size then error(("lz4_block returned %d bytes for %d"):format(#out, size), 0) end
  else ok, out = pcall(region.lz4_stream, s) end
  if ok then
    assert(type(out) == "string", "decompression returned no string")
    data.xxhash32(out)
  elseif type(out) ~= "string" or not out:find(prefixes[mode + 1]) then
    error("unexpected error: " .. tostring(out), 0)
  end
end
)lua";

std::unique_ptr<torte::fuzz::FuzzLua> g_lua;

struct Args {
  const uint8_t* data;
  size_t size;
};

int run(lua_State* L) {
  auto* a = static_cast<Args*>(lua_touserdata(L, 1));
  torte::fuzz::FuzzInput in(a->data, a->size);
  const int mode = in.byte() % 4;
  const uint16_t size = mode == 2 ? in.u16() : 0;
  const std::string_view rest = in.rest();
  lua_getfield(L, LUA_REGISTRYINDEX, "torte.fuzz.inflate");
  lua_pushinteger(L, mode);
  lua_pushlstring(L, rest.data(), rest.size());
  lua_pushinteger(L, size);
  lua_call(L, 3, 0);
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_lua = std::make_unique<torte::fuzz::FuzzLua>();
  std::string error;
  if (!g_lua->run(kDriver, &error)) torte::fuzz::broken_promise("inflate driver: " + error);
  lua_setfield(g_lua->state(), LUA_REGISTRYINDEX, "torte.fuzz.inflate");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Args args{data, size};
  g_lua->set_instruction_budget(5'000'000);
  std::string error;
  if (!g_lua->call(run, &args, &error)) torte::fuzz::broken_promise("inflate: " + error);
  lua_settop(g_lua->state(), 0);
  lua_gc(g_lua->state(), LUA_GCSTEP, 0);
  return 0;
}
