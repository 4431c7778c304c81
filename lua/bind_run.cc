// What a script learns about its run and may change in it: torte.script_dir, torte.quick, the SIMD target
// (torte.simd.*), the --list-args listing of torte.options, and the strict torte tables that name a misspelled
// function instead of returning nil.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "binding.h"
#include "runtime.h"
#include "simd/simd_target.h"
#include "types.h"

namespace torte::lua {

namespace {

// torte.simd.targets() -> the targets this CPU runs (names torte.simd.use and --simd take), best first.
int l_targets(lua_State* L) {
  lua_newtable(L);
  lua_Integer i = 0;
  for (const simd::TargetInfo& t : simd::compiled_targets())
    if (t.supported) {
      lua_pushstring(L, t.name.c_str());
      lua_rawseti(L, -2, ++i);
    }
  return 1;
}

// torte.simd.use(name) -> the target now chosen; later renders and kernels run on it ("auto": the best).
int l_use(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error("torte.simd.use expects a target name, got " + type_name(L, 1));
  try {
    simd::use_target(lua_tostring(L, 1));
  } catch (const Error& e) {
    throw Error(std::string("torte.simd.use: ") + e.what());
  }
  lua_pushstring(L, simd::current_target().c_str());
  return 1;
}

// torte.simd.current() -> the target kernels dispatch to now ("avx2").
int l_current(lua_State* L) {
  lua_pushstring(L, simd::current_target().c_str());
  return 1;
}

// The names of the table at `index`, sorted, as "a, b, c".
std::string known_names(lua_State* L, int index) {
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, index)) {
    if (lua_type(L, -2) == LUA_TSTRING) names.push_back(lua_tostring(L, -2));
    lua_pop(L, 1);
  }
  std::sort(names.begin(), names.end());
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// __index of a strict table (upvalue 1: its name, "torte.material"): a missing name is an error at the line
// that asked for it.
int strict_index(lua_State* L) {
  const char* table = lua_tostring(L, lua_upvalueindex(1));
  const std::string key = lua_type(L, 2) == LUA_TSTRING ? std::string("'") + lua_tostring(L, 2) + "'"
                                                        : "key of type " + type_name(L, 2);
  const std::string known = known_names(L, 1);
  luaL_where(L, 2);  // the script line that indexed, not this C function
  return luaL_error(L, "%s%s has no %s (known: %s)", lua_tostring(L, -1), table, key.c_str(), known.c_str());
}

void make_strict(lua_State* L, int index, const std::string& name, int depth) {
  index = lua_absindex(L, index);
  if (lua_getmetatable(L, index)) {  // tables with a behaviour of their own keep it
    lua_pop(L, 1);
    return;
  }
  if (depth < 2) {
    lua_pushnil(L);
    while (lua_next(L, index)) {
      // torte.args holds what the command line gave: absent keys are nil there, as scripts expect.
      if (lua_type(L, -2) == LUA_TSTRING && lua_type(L, -1) == LUA_TTABLE && std::string(lua_tostring(L, -2)) != "args")
        make_strict(L, -1, name + "." + lua_tostring(L, -2), depth + 1);
      lua_pop(L, 1);
    }
  }
  lua_newtable(L);
  lua_pushstring(L, name.c_str());
  lua_pushcclosure(L, strict_index, 1);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, index);
}

std::string lua_value_text(lua_State* L, int index) {
  switch (lua_type(L, index)) {
    case LUA_TSTRING: return std::string("\"") + lua_tostring(L, index) + "\"";
    case LUA_TBOOLEAN: return lua_toboolean(L, index) ? "true" : "false";
    case LUA_TNUMBER: {
      std::string out = luaL_tolstring(L, index, nullptr);
      lua_pop(L, 1);
      return out;
    }
    default: return type_name(L, index);
  }
}

// torte._list_args(defaults), present under --list-args only: what torte.options calls first (the prelude).
int l_list_args(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  list_arguments(L, 1);
}

}  // namespace

void open_run(lua_State* L, int torte_index, const std::string& script_dir, bool quick, bool list_args) {
  lua_pushstring(L, script_dir.c_str());
  lua_setfield(L, torte_index, "script_dir");
  lua_pushboolean(L, quick);
  lua_setfield(L, torte_index, "quick");
  const luaL_Reg fns[] = {{"targets", guarded<l_targets>}, {"use", guarded<l_use>}, {"current", guarded<l_current>},
                          {nullptr, nullptr}};
  if (list_args) {
    lua_pushcfunction(L, l_list_args);
    lua_setfield(L, torte_index, "_list_args");
  }
  push_subtable(L, torte_index, "simd");
  set_functions(L, fns);
  lua_pop(L, 1);
}

void make_api_strict(lua_State* L) {
  lua_getglobal(L, "torte");
  make_strict(L, -1, "torte", 0);
  lua_pop(L, 1);
}

void list_arguments(lua_State* L, int index) {
  RunContext& ctx = run_context(L);
  index = lua_absindex(L, index);
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, index)) {
    names.push_back(luaL_tolstring(L, -2, nullptr));
    lua_pop(L, 2);
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) std::printf("this scene declares no arguments (torte.options)\n");
  for (const std::string& n : names) {
    lua_getfield(L, index, n.c_str());
    const char* type = lua_type(L, -1) == LUA_TNUMBER ? (lua_isinteger(L, -1) ? "integer" : "number")
                                                      : lua_typename(L, lua_type(L, -1));
    std::printf("%-20s %-9s default %s\n", n.c_str(), type, lua_value_text(L, -1).c_str());
    lua_pop(L, 1);
  }
  std::fflush(stdout);
  ctx.args_listed = true;
  luaL_error(L, "the scene's arguments were listed (--list-args)");
  std::abort();  // luaL_error does not return
}

}  // namespace torte::lua
