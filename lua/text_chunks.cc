#include "text_chunks.h"

#include <cstring>
#include <string>

#include "binding.h"
#include "file_access.h"

namespace torte::lua {

namespace {

// Lua's own refusal under mode "t" ("attempt to load a binary chunk (mode is 't')") names no file.
bool is_binary_refusal(lua_State* L, int idx) {
  const char* msg = lua_tostring(L, idx);
  return msg && std::strstr(msg, "attempt to load a binary chunk");
}

const char kRefusal[] = "precompiled Lua chunks are not accepted, only Lua source text";

// load(chunk [, chunkname [, mode [, env]]]): the library's load (upvalue 1) with mode "t" whatever was asked.
int text_load(lua_State* L) {
  if (lua_gettop(L) < 3) lua_settop(L, 3);  // a missing chunkname becomes nil, which load treats as absent
  lua_pushliteral(L, "t");
  lua_replace(L, 3);
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  if (lua_gettop(L) >= 2 && lua_isnil(L, 1) && is_binary_refusal(L, 2)) {
    lua_pushfstring(L, "load: %s", kRefusal);
    lua_replace(L, 2);
  }
  return lua_gettop(L);
}

// loadfile([filename [, mode [, env]]]): the chunk, or nil and a message.
int text_loadfile(lua_State* L) {
  const char* file = luaL_optstring(L, 1, nullptr);
  const bool has_env = !lua_isnone(L, 3);
  if (file) check_read(L, file, "loadfile");
  if (load_text_file(L, file) != LUA_OK) {
    lua_pushnil(L);
    lua_insert(L, -2);
    return 2;
  }
  if (has_env) {
    lua_pushvalue(L, 3);
    if (!lua_setupvalue(L, -2, 1)) lua_pop(L, 1);  // the chunk's first upvalue is its _ENV
  }
  return 1;
}

// dofile([filename]): runs the file and returns what it returns; errors propagate.
int text_dofile(lua_State* L) {
  const char* file = luaL_optstring(L, 1, nullptr);
  const std::string name = file ? file : "";
  lua_settop(L, 1);
  if (file) check_read(L, name, "dofile");
  if (load_text_file(L, file ? name.c_str() : nullptr) != LUA_OK) return lua_error(L);
  lua_call(L, 0, LUA_MULTRET);
  return lua_gettop(L) - 1;
}

// package.searchers[2]: finds name on package.path (upvalue 1: the package table) with the library's own
// searchpath (upvalue 2, kept so a script replacing package.searchpath changes nothing here).
int text_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  lua_pushvalue(L, lua_upvalueindex(2));
  lua_pushstring(L, name);
  if (lua_getfield(L, lua_upvalueindex(1), "path") != LUA_TSTRING) luaL_error(L, "'package.path' must be a string");
  lua_call(L, 2, 2);
  if (lua_type(L, -2) != LUA_TSTRING) return 1;  // not found: the message lists the files tried
  const std::string file = lua_tostring(L, -2);
  check_read(L, file, "require");
  if (load_text_file(L, file.c_str()) != LUA_OK)
    luaL_error(L, "error loading module '%s' from file '%s': %s", name, file.c_str(), lua_tostring(L, -1));
  lua_pushstring(L, file.c_str());
  return 2;
}

}  // namespace

int load_text_file(lua_State* L, const char* path) {
  const int status = luaL_loadfilex(L, path, "t");
  if (status != LUA_OK && is_binary_refusal(L, -1)) {
    lua_pop(L, 1);
    lua_pushfstring(L, "%s: %s", path ? path : "stdin", kRefusal);
  }
  return status;
}

void install_text_loaders(lua_State* L) {
  lua_getglobal(L, "load");
  lua_pushcclosure(L, text_load, 1);
  lua_setglobal(L, "load");
  lua_pushcfunction(L, guarded<text_loadfile>);
  lua_setglobal(L, "loadfile");
  lua_pushcfunction(L, guarded<text_dofile>);
  lua_setglobal(L, "dofile");
  if (lua_getglobal(L, "package") == LUA_TTABLE) {
    if (lua_getfield(L, -1, "searchers") == LUA_TTABLE) {
      lua_pushvalue(L, -2);
      lua_getfield(L, -3, "searchpath");
      lua_pushcclosure(L, guarded<text_searcher>, 2);
      lua_rawseti(L, -2, 2);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

}  // namespace torte::lua
