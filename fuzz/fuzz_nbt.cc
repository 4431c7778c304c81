// NBT (torte.data.nbt, lua/bind_data.cc) through the Lua binding. Input: 4 parameter bytes (offset, bits,
// count, padded for unpack_bits), then the NBT bytes. Every root tag in the string is decoded in turn (the next
// offset each returns); the values are walked, long arrays indexed, listed and unpacked. Errors must come from
// the binding ("torte.data.nbt: ..." and the other torte.data functions' names).
#include <lauxlib.h>

#include <memory>
#include <string>

#include "error_checks.h"
#include "harness.h"
#include "fuzz_input.h"
#include "fuzz_support.h"

namespace {

const char kDriver[] = R"lua(
local data = torte.data
return function(s, offset, bits, count, padded)
  local budget = 20000
  local function walk(x, depth)
    budget = budget - 1
    if budget < 0 or depth > 600 then return end
    local t = type(x)
    if t == "table" then
      for _, y in pairs(x) do walk(y, depth + 1) end
    elseif t == "userdata" then
      local n = #x
      local _ = x[1], x[n], x[0], x[n + 1], tostring(x)
      local ok, err = pcall(function() return x[1.5] end)
      if not ok and not err:find("torte%.data%.longs has no field") then error(err, 0) end
      if n <= 4096 then x:table() end
      local ok, err = pcall(x.unpack_bits, x, bits, count, padded)
      if not ok and not err:find("^torte%.data%.unpack_bits") then error(err, 0) end
    elseif t == "string" and #x > 0 then
      local ok, err = pcall(data.unpack_bits, x, bits, count, padded)
      if not ok and not err:find("^torte%.data%.unpack_bits") then error(err, 0) end
    end
  end
  local roots = 0
  while offset <= #s and roots < 8 do
    local ok, value, name, next_offset = pcall(data.nbt, s, offset)
    if not ok then
      if type(value) ~= "string" or not value:find("^torte%.data%.nbt") then error("bad nbt error: " .. tostring(value), 0) end
      return
    end
    assert(type(name) == "string", "nbt returned no name")
    assert(math.type(next_offset) == "integer" and next_offset > offset and next_offset <= #s + 1, "bad next offset")
    walk(value, 0)
    offset, roots = next_offset, roots + 1
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
  const uint8_t offset = in.byte() % 4, bits = in.byte(), count_code = in.byte(), padded = in.byte();
  const std::string_view nbt = in.rest();
  lua_getfield(L, LUA_REGISTRYINDEX, "torte.fuzz.nbt");
  lua_pushlstring(L, nbt.data(), nbt.size());
  lua_pushinteger(L, 1 + offset);
  lua_pushinteger(L, bits % 40);  // 1..32 are valid; others must be refused
  lua_pushinteger(L, count_code < 250 ? lua_Integer(count_code) * 17 : lua_Integer(count_code - 250) << 22);
  lua_pushboolean(L, padded & 1);
  lua_call(L, 5, 0);
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_lua = std::make_unique<torte::fuzz::FuzzLua>();
  std::string error;
  if (!g_lua->run(kDriver, &error)) torte::fuzz::broken_promise("nbt driver: " + error);
  lua_setfield(g_lua->state(), LUA_REGISTRYINDEX, "torte.fuzz.nbt");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Args args{data, size};
  g_lua->set_instruction_budget(5'000'000);
  std::string error;
  if (!g_lua->call(run, &args, &error)) torte::fuzz::broken_promise("nbt: " + error);
  lua_settop(g_lua->state(), 0);
  lua_gc(g_lua->state(), LUA_GCSTEP, 0);
  return 0;
}
