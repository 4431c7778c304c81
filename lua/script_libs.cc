#include "script_libs.h"

#include <cstring>
#include <string>

#include "binding.h"
#include "file_access.h"
#include "script_limits.h"
#include "text_chunks.h"

namespace torte::lua {

namespace {

// Calls upvalue 1 (the library's own function) with this call's arguments and returns all it returns.
int call_original(lua_State* L) {
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

// Replaces table[name] (the table on the top of the stack) by `wrapper` with the old function as upvalue 1.
void wrap_field(lua_State* L, const char* name, lua_CFunction wrapper) {
  lua_getfield(L, -1, name);
  lua_pushcclosure(L, wrapper, 1);
  lua_setfield(L, -2, name);
}

void remove_fields(lua_State* L, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    lua_pushnil(L);
    lua_setfield(L, -2, name);
  }
}

// ---- debug, hardened ----------------------------------------------------------------------------------------
// The C code of Lua's libraries (and torte's) trusts the types of its upvalues, of the values in its stack
// frames and of a userdata with its metatable; the debug library could change all three.

int debug_setmetatable(lua_State* L) {
  if (lua_type(L, 1) == LUA_TUSERDATA)
    throw Error("debug.setmetatable: the metatable of a userdata (" + type_name(L, 1) + ") cannot be changed");
  return call_original(L);
}

template <const char* kName>
int debug_upvalue(lua_State* L) {
  if (lua_iscfunction(L, 1))
    throw Error(std::string("debug.") + kName + ": the upvalues of C functions are not accessible");
  return call_original(L);
}
constexpr char kGetUpvalue[] = "getupvalue";
constexpr char kSetUpvalue[] = "setupvalue";

// The frame `level` of debug.getlocal/setlocal ([thread,] level, n, ...) in `co`; throws for a C function's frame.
lua_Debug lua_frame(lua_State* L, lua_State* co, int arg, const char* function) {
  lua_Debug ar;
  const lua_Integer level = luaL_checkinteger(L, arg);
  if (level < 0 || level > 1000000 || !lua_getstack(co, int(level), &ar)) luaL_argerror(L, arg, "level out of range");
  lua_getinfo(co, "S", &ar);
  if (std::strcmp(ar.what, "C") == 0)
    throw Error(std::string("debug.") + function + ": the locals of C functions are not accessible");
  return ar;
}

// debug.getlocal([thread,] f | level, n): as the library's, for frames of Lua functions.
int debug_getlocal(lua_State* L) {
  const bool thread = lua_isthread(L, 1);
  lua_State* co = thread ? lua_tothread(L, 1) : L;
  const int arg = thread ? 2 : 1;
  if (lua_isfunction(L, arg)) return call_original(L);  // parameter names of a function: no values
  lua_Debug ar = lua_frame(L, co, arg, "getlocal");
  const int n = int(luaL_checkinteger(L, arg + 1));
  if (co != L && !lua_checkstack(co, 1)) luaL_error(L, "stack overflow");  // an error of co would not be ours
  const char* name = lua_getlocal(co, &ar, n);
  if (!name) {
    lua_pushnil(L);
    return 1;
  }
  lua_xmove(co, L, 1);
  lua_pushstring(L, name);
  lua_rotate(L, -2, 1);
  return 2;
}

// debug.setlocal([thread,] level, n, value): named locals of Lua functions only; Lua's temporaries ("(for
// state)", "(temporary)") are the VM's and stay as it left them.
int debug_setlocal(lua_State* L) {
  const bool thread = lua_isthread(L, 1);
  lua_State* co = thread ? lua_tothread(L, 1) : L;
  const int arg = thread ? 2 : 1;
  lua_Debug ar = lua_frame(L, co, arg, "setlocal");
  const int n = int(luaL_checkinteger(L, arg + 1));
  luaL_checkany(L, arg + 2);
  lua_settop(L, arg + 2);
  if (co != L && !lua_checkstack(co, 1)) luaL_error(L, "stack overflow");
  if (const char* peek = lua_getlocal(co, &ar, n)) {
    const bool temporary = peek[0] == '(';
    lua_pop(co, 1);
    if (temporary) throw Error("debug.setlocal: Lua's internal slots cannot be set");
  }
  lua_xmove(L, co, 1);
  const char* name = lua_setlocal(co, &ar, n);
  if (!name) lua_pop(co, 1);
  lua_pushstring(L, name);
  return 1;
}

void harden_debug(lua_State* L) {
  remove_fields(L, {"getregistry"});
  wrap_field(L, "setmetatable", guarded<debug_setmetatable>);
  wrap_field(L, "getupvalue", guarded<debug_upvalue<kGetUpvalue>>);
  wrap_field(L, "setupvalue", guarded<debug_upvalue<kSetUpvalue>>);
  wrap_field(L, "getlocal", guarded<debug_getlocal>);
  wrap_field(L, "setlocal", guarded<debug_setlocal>);
}

// ---- the file policy in io and os ---------------------------------------------------------------------------

int io_open(lua_State* L) {
  const char* file = luaL_checkstring(L, 1);
  const char* mode = luaL_optstring(L, 2, "r");
  if (std::strpbrk(mode, "wa+"))
    check_write(L, file, "io.open");
  else
    check_read(L, file, "io.open");
  return call_original(L);
}

template <const char* kName, bool kWrite>
int io_named(lua_State* L) {  // io.lines, io.input, io.output: a file name, a file or nothing
  if (lua_type(L, 1) == LUA_TSTRING) {
    if (kWrite)
      check_write(L, lua_tostring(L, 1), kName);
    else
      check_read(L, lua_tostring(L, 1), kName);
  }
  return call_original(L);
}
constexpr char kLines[] = "io.lines";
constexpr char kInput[] = "io.input";
constexpr char kOutput[] = "io.output";

int os_remove(lua_State* L) {
  check_write(L, luaL_checkstring(L, 1), "os.remove");
  return call_original(L);
}

int os_rename(lua_State* L) {
  check_write(L, luaL_checkstring(L, 1), "os.rename");  // the old name goes away: as much a write as the new
  check_write(L, luaL_checkstring(L, 2), "os.rename");
  return call_original(L);
}

// setmetatable(t, mt) without finalizers: Lua runs __gc with hooks off, so a finalizer would escape the
// instruction budget and Ctrl-C. Lua marks a table for finalization only when its metatable has __gc at this
// call, so checking here is enough.
int base_setmetatable(lua_State* L) {
  if (lua_type(L, 2) == LUA_TTABLE) {
    lua_pushliteral(L, "__gc");
    const bool finalizer = lua_rawget(L, 2) != LUA_TNIL;
    lua_pop(L, 1);
    if (finalizer)
      throw Error("setmetatable: __gc metamethods are not available under --sandbox (finalizers run outside the "
                  "instruction limit and Ctrl-C)");
  }
  return call_original(L);
}

void sandbox_libraries(lua_State* L) {
  lua_pushglobaltable(L);
  wrap_field(L, "setmetatable", guarded<base_setmetatable>);
  lua_pop(L, 1);
  if (lua_getglobal(L, "os") == LUA_TTABLE) {
    remove_fields(L, {"execute", "exit", "getenv", "tmpname", "setlocale"});
    wrap_field(L, "remove", guarded<os_remove>);
    wrap_field(L, "rename", guarded<os_rename>);
  }
  lua_pop(L, 1);
  if (lua_getglobal(L, "io") == LUA_TTABLE) {
    remove_fields(L, {"popen", "tmpfile"});
    wrap_field(L, "open", guarded<io_open>);
    wrap_field(L, "lines", guarded<io_named<kLines, false>>);
    wrap_field(L, "input", guarded<io_named<kInput, false>>);
    wrap_field(L, "output", guarded<io_named<kOutput, true>>);
  }
  lua_pop(L, 1);
  if (lua_getglobal(L, "package") == LUA_TTABLE) {
    remove_fields(L, {"loadlib"});
    lua_pushliteral(L, "");
    lua_setfield(L, -2, "cpath");
    if (lua_getfield(L, -1, "searchers") == LUA_TTABLE) {  // keep preload and the text-only Lua searcher
      for (lua_Integer i = luaL_len(L, -1); i > 2; --i) {
        lua_pushnil(L);
        lua_rawseti(L, -2, i);
      }
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  // debug: getinfo (older scenes found their own directory with debug.getinfo(1, "S").source; torte.script_dir
  // says it now) and traceback; nothing that changes a value or reaches the registry.
  lua_newtable(L);
  if (lua_getglobal(L, "debug") == LUA_TTABLE) {
    for (const char* keep : {"getinfo", "traceback"}) {
      lua_getfield(L, -1, keep);
      lua_setfield(L, -3, keep);
    }
  }
  lua_pop(L, 1);
  lua_pushvalue(L, -1);
  lua_setglobal(L, "debug");
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  lua_insert(L, -2);
  lua_setfield(L, -2, "debug");  // require "debug" gives the same table
  lua_pop(L, 1);
}

}  // namespace

void open_script_libraries(lua_State* L, bool sandboxed) {
  luaL_openlibs(L);
  install_text_loaders(L);
  track_coroutines(L);
  if (lua_getglobal(L, "debug") == LUA_TTABLE) harden_debug(L);
  lua_pop(L, 1);
  if (sandboxed) sandbox_libraries(L);
}

}  // namespace torte::lua
