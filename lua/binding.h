// Helpers shared by the Lua bindings: keyword-table checking, userdata that own C++ objects, and the guard that
// turns C++ exceptions into Lua errors with the script's file and line.
//
// We use Debian's C++ build of Lua (lua5.4-c++): lua_error unwinds with a C++ exception, so destructors of
// objects alive in a binding run when a Lua error passes through it.
#pragma once
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rgb.h"
#include "core/transform.h"

namespace torte::lua {

// Runs a binding body; torte::Error and std::exception become a Lua error at the caller's location.
template <int (*Body)(lua_State*)>
int guarded(lua_State* L) {
  std::string message;
  try {
    return Body(L);
  } catch (const std::exception& e) {
    message = e.what();
  }
  return luaL_error(L, "%s", message.c_str());
}

// ---- userdata owning a std::shared_ptr<T>; T's metatable is named by LuaName<T>::value -----------------
template <class T>
struct LuaName;
template <>
struct LuaName<Transform> {
  static constexpr const char* value = "torte.transform";
};

template <class T>
void push_object(lua_State* L, std::shared_ptr<T> object) {
  void* mem = lua_newuserdatauv(L, sizeof(std::shared_ptr<T>), 0);
  new (mem) std::shared_ptr<T>(std::move(object));
  if (luaL_newmetatable(L, LuaName<T>::value)) {
    lua_pushcfunction(L, [](lua_State* L2) -> int {
      // Only ever called by the collector on a live T, but check anyway: a script must not be able to crash us.
      if (auto* p = static_cast<std::shared_ptr<T>*>(luaL_testudata(L2, 1, LuaName<T>::value))) p->reset();
      return 0;
    });
    lua_setfield(L, -2, "__gc");
    lua_pushstring(L, LuaName<T>::value);
    lua_setfield(L, -2, "__name");
    // getmetatable() returns this string instead of the table, so scripts cannot call __gc or __index directly.
    lua_pushstring(L, LuaName<T>::value);
    lua_setfield(L, -2, "__metatable");
  }
  lua_setmetatable(L, -2);
}

// The object at idx if it is a T, else nullptr.
template <class T>
std::shared_ptr<T> to_object(lua_State* L, int idx) {
  auto* p = static_cast<std::shared_ptr<T>*>(luaL_testudata(L, idx, LuaName<T>::value));
  return p ? *p : nullptr;  // a collected (reset) object also comes back as nullptr
}

// Name of a Lua value's type for error messages (torte types by their own names).
std::string type_name(lua_State* L, int idx);

// ---- keyword arguments -----------------------------------------------------------------------------------
// Reads fields of the table at `index`; finish() rejects keys that were never read, so a typo is an error that
// names the key. Getters throw torte::Error("<function>: ...") and the guard adds the script location.
class KwArgs {
 public:
  KwArgs(lua_State* L, int index, std::string function);
  bool has(const char* key);
  double number(const char* key);
  double number(const char* key, double fallback);
  int integer(const char* key, int fallback);
  bool boolean(const char* key, bool fallback);
  std::string string(const char* key);
  std::string string(const char* key, const std::string& fallback);
  Vec3f vec3(const char* key);
  Vec3f vec3(const char* key, Vec3f fallback);
  // A colour: {r, g, b} or one number for grey.
  Rgb rgb(const char* key, Rgb fallback);
  Transform transform(const char* key);  // identity when absent
  std::vector<double> numbers(const char* key);  // a flat array; nested {x,y,z} entries are flattened
  // A torte object of type T; required unless `optional`.
  template <class T>
  std::shared_ptr<T> object(const char* key, bool optional = false);
  // Pushes the raw value of key (nil when absent) and marks it read.
  void push(const char* key);
  // Throws if the table holds keys that were not read.
  void finish();
  [[noreturn]] void fail(const char* key, const std::string& problem) const;
  const std::string& function() const { return function_; }
  lua_State* state() const { return L_; }

 private:
  bool fetch(const char* key);  // pushes the value; returns false (and pops) when nil
  lua_State* L_;
  int index_;
  std::string function_;
  std::set<std::string> read_;
};

template <class T>
std::shared_ptr<T> KwArgs::object(const char* key, bool optional) {
  if (!fetch(key)) {
    if (optional) return nullptr;
    fail(key, std::string("is required (a ") + LuaName<T>::value + ")");
  }
  std::shared_ptr<T> p = to_object<T>(L_, -1);
  if (!p) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, std::string("must be a ") + LuaName<T>::value + ", got " + got);
  }
  lua_pop(L_, 1);
  return p;
}

// Reads a Vec3 from {x, y, z} at idx; throws with `what` in the message.
Vec3f check_vec3(lua_State* L, int idx, const std::string& what);

// Registers functions into the table at the top of the stack.
void set_functions(lua_State* L, const luaL_Reg* functions);
// Ensures torte.<name> exists as a table and leaves it on the stack (torte table must be at `torte_index`).
void push_subtable(lua_State* L, int torte_index, const char* name);

}  // namespace torte::lua
