#include "binding.h"

#include <atomic>
#include <cmath>
#include <cstdlib>

#include "core/memory_budget.h"
#include "core/text.h"
#include "script_limits.h"

namespace torte::lua {

UserdataHeader* tagged_userdata(lua_State* L, int idx, const void* tag) {
  if (lua_type(L, idx) != LUA_TUSERDATA || lua_rawlen(L, idx) < sizeof(UserdataHeader)) return nullptr;
  auto* h = static_cast<UserdataHeader*>(lua_touserdata(L, idx));
  if (h->magic != UserdataHeader::kMagic || (tag && h->tag != tag)) return nullptr;
  return h;
}

// One collector for every torte type: it releases what the userdata's own header says it holds, so a userdata
// that was given another type's metatable is still released as what it is.
int collect_tagged(lua_State* L) {
  if (UserdataHeader* h = tagged_userdata(L, 1, nullptr)) {
    if (auto release = h->release) {
      h->release = nullptr;  // a finalizer can run again on a resurrected object
      release(h);
    }
  }
  return 0;
}

void set_tagged_metatable(lua_State* L, const UserdataHeader& header) {
  if (luaL_newmetatable(L, header.name)) {
    lua_pushcfunction(L, collect_tagged);
    lua_setfield(L, -2, "__gc");
    lua_pushstring(L, header.name);
    lua_setfield(L, -2, "__name");
    // getmetatable() returns this string instead of the table, so scripts cannot call __gc or __index directly.
    lua_pushstring(L, header.name);
    lua_setfield(L, -2, "__metatable");
  }
  lua_setmetatable(L, -2);
}

void raise_binding_failure(lua_State* L, const BindingFailure& failure) {
  switch (failure.kind) {
    case BindingFailure::kInterrupted:
      raise_interrupted(L, failure.message);
    case BindingFailure::kOutOfMemory: {
      // Name the binding as the script called it (torte.mesh.load is called as 'load').
      lua_Debug ar;
      std::string name = "a torte function";
      if (lua_getstack(L, 0, &ar) && lua_getinfo(L, "n", &ar) && ar.name)
        name = std::string("'") + ar.name + "'";
      std::string detail = failure.message.empty() ? "" : " (" + failure.message + ")";
      luaL_error(L, "out of memory while running %s%s; the process may use up to %s (--max-memory)", name.c_str(),
                 detail.c_str(), format_bytes(memory_limit()).c_str());
    }
    case BindingFailure::kError:
      break;
  }
  luaL_error(L, "%s", failure.message.c_str());
  std::abort();  // luaL_error does not return
}

std::string type_name(lua_State* L, int idx) {
  // A torte userdata is named by its own tag: its metatable may have been swapped.
  if (const UserdataHeader* h = tagged_userdata(L, idx, nullptr)) return h->name;
  if (lua_getmetatable(L, idx)) {
    lua_getfield(L, -1, "__name");
    std::string name = lua_isstring(L, -1) ? lua_tostring(L, -1) : "";
    lua_pop(L, 2);
    if (!name.empty()) return name;
  }
  return luaL_typename(L, idx);
}

KwArgs::KwArgs(lua_State* L, int index, std::string function)
    : L_(L), index_(lua_absindex(L, index)), function_(std::move(function)) {
  if (!lua_istable(L, index_))
    throw Error(function_ + " expects a table of keyword arguments, e.g. " + function_ + "{...}, got " +
                type_name(L, index_));
}

void KwArgs::fail(const char* key, const std::string& problem) const {
  throw Error(function_ + ": '" + key + "' " + problem);
}

bool KwArgs::fetch(const char* key) {
  read_.insert(key);
  if (lua_getfield(L_, index_, key) == LUA_TNIL) {
    lua_pop(L_, 1);
    return false;
  }
  return true;
}

void KwArgs::push(const char* key) {
  read_.insert(key);
  lua_getfield(L_, index_, key);
}

bool KwArgs::has(const char* key) {
  const bool present = lua_getfield(L_, index_, key) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

double KwArgs::number(const char* key) {
  if (!fetch(key)) fail(key, "is required (a number)");
  if (lua_type(L_, -1) != LUA_TNUMBER) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, "must be a number, got " + got);
  }
  const double v = lua_tonumber(L_, -1);
  lua_pop(L_, 1);
  if (!std::isfinite(v)) fail(key, "must be finite");
  return v;
}

double KwArgs::number(const char* key, double fallback) { return has(key) ? number(key) : (read_.insert(key), fallback); }

int KwArgs::integer(const char* key, int fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const double v = number(key);
  if (v != std::floor(v) || std::fabs(v) > 2147483647.0) fail(key, "must be an integer, got " + std::to_string(v));
  return int(v);
}

bool KwArgs::boolean(const char* key, bool fallback) {
  if (!fetch(key)) return fallback;
  if (!lua_isboolean(L_, -1)) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, "must be true or false, got " + got);
  }
  const bool v = lua_toboolean(L_, -1);
  lua_pop(L_, 1);
  return v;
}

std::string KwArgs::string(const char* key) {
  if (!fetch(key)) fail(key, "is required (a string)");
  if (lua_type(L_, -1) != LUA_TSTRING) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, "must be a string, got " + got);
  }
  std::string v = lua_tostring(L_, -1);
  lua_pop(L_, 1);
  return v;
}

std::string KwArgs::string(const char* key, const std::string& fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  return string(key);
}

Vec3f check_vec3(lua_State* L, int idx, const std::string& what) {
  idx = lua_absindex(L, idx);
  if (!lua_istable(L, idx)) throw Error(what + " must be a table {x, y, z}, got " + type_name(L, idx));
  if (lua_rawlen(L, idx) != 3) throw Error(what + " must have exactly 3 numbers {x, y, z}");
  Vec3f v;
  for (int i = 0; i < 3; ++i) {
    lua_rawgeti(L, idx, i + 1);
    int ok = 0;
    v[i] = float(lua_tonumberx(L, -1, &ok));
    lua_pop(L, 1);
    if (!ok || !std::isfinite(v[i])) throw Error(what + " must hold 3 finite numbers");
  }
  return v;
}

Vec3f KwArgs::vec3(const char* key) {
  if (!fetch(key)) fail(key, "is required (a table {x, y, z})");
  Vec3f v;
  try {
    v = check_vec3(L_, -1, function_ + ": '" + key + "'");
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
  lua_pop(L_, 1);
  return v;
}

Vec3f KwArgs::vec3(const char* key, Vec3f fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  return vec3(key);
}

Rgb KwArgs::rgb(const char* key, Rgb fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  Rgb c;
  if (fetch(key) && lua_type(L_, -1) == LUA_TNUMBER) {
    c = Rgb(float(lua_tonumber(L_, -1)));
    lua_pop(L_, 1);
  } else {
    Vec3f v;
    try {
      v = check_vec3(L_, -1, function_ + ": '" + key + "' (a colour {r, g, b} or a number)");
    } catch (...) {
      lua_pop(L_, 1);
      throw;
    }
    lua_pop(L_, 1);
    c = Rgb(v.x, v.y, v.z);
  }
  if (!c.is_finite() || c.r < 0 || c.g < 0 || c.b < 0) fail(key, "must be finite and non-negative");
  return c;
}

Transform KwArgs::transform(const char* key) {
  auto t = object<Transform>(key, true);
  return t ? *t : Transform();
}

std::vector<double> KwArgs::numbers(const char* key) {
  if (!fetch(key)) fail(key, "is required (an array of numbers)");
  if (!lua_istable(L_, -1)) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, "must be an array of numbers, got " + got);
  }
  std::vector<double> out;
  const lua_Integer n = lua_Integer(lua_rawlen(L_, -1));
  // A table's length can be a border far past its entries ({[1] = 1, [2] = 2, [4] = 4, ..., [2^40] = 1} has
  // length 2^40): reserve at most 2^20 entries up front; a real array grows the vector as its entries are read,
  // a sparse one fails at its first missing entry.
  out.reserve(size_t(std::min<lua_Integer>(n, lua_Integer(1) << 20)));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L_, -1, i);
    if (lua_istable(L_, -1)) {  // nested {x, y, z}: flatten
      const lua_Integer m = lua_Integer(lua_rawlen(L_, -1));
      for (lua_Integer j = 1; j <= m; ++j) {
        lua_rawgeti(L_, -1, j);
        int ok = 0;
        const double v = lua_tonumberx(L_, -1, &ok);
        lua_pop(L_, 1);
        if (!ok) {
          lua_pop(L_, 2);
          fail(key, "entry " + std::to_string(i) + " holds a value that is not a number");
        }
        out.push_back(v);
      }
    } else {
      int ok = 0;
      const double v = lua_tonumberx(L_, -1, &ok);
      if (!ok) {
        lua_pop(L_, 2);
        fail(key, "entry " + std::to_string(i) + " is not a number");
      }
      out.push_back(v);
    }
    lua_pop(L_, 1);
  }
  lua_pop(L_, 1);
  return out;
}

namespace {
std::atomic<KeyObserver> key_observer{nullptr};
}  // namespace

void set_key_observer(KeyObserver observer) { key_observer.store(observer); }

void KwArgs::finish() {
  if (KeyObserver observe = key_observer.load()) observe(function_, read_);
  std::string unknown;
  bool found = false;  // not unknown.empty(): "" is a key too
  lua_pushnil(L_);
  while (lua_next(L_, index_) != 0) {
    lua_pop(L_, 1);  // value
    if (lua_type(L_, -1) != LUA_TSTRING) {
      lua_pop(L_, 1);
      throw Error(function_ + ": positional values are not accepted; pass key = value pairs");
    }
    // With its length: a key holding a NUL byte is not the keyword before the NUL.
    size_t len = 0;
    const char* s = lua_tolstring(L_, -1, &len);
    std::string key(s, len);
    // The smallest unknown key, not the first lua_next gives: that order changes from run to run.
    if (!read_.count(key) && (!found || key < unknown)) {
      unknown = std::move(key);
      found = true;
    }
  }
  if (!found) return;
  std::string known;
  for (const std::string& k : read_) known += (known.empty() ? "" : ", ") + k;
  throw Error(function_ + ": unknown key '" + escape_text(unknown) + "' (accepted keys: " + known + ")");
}

void set_functions(lua_State* L, const luaL_Reg* functions) { luaL_setfuncs(L, functions, 0); }

void set_methods(lua_State* L, const luaL_Reg* methods) {
  lua_newtable(L);
  set_functions(L, methods);
  lua_setfield(L, -2, "__methods");
}

bool push_method(lua_State* L, int idx, const std::string& key) {
  const UserdataHeader* h = tagged_userdata(L, idx, nullptr);
  if (!h) return false;
  if (luaL_getmetatable(L, h->name) != LUA_TTABLE) {
    lua_pop(L, 1);
    return false;
  }
  if (lua_getfield(L, -1, "__methods") != LUA_TTABLE) {
    lua_pop(L, 2);
    return false;
  }
  lua_pushlstring(L, key.data(), key.size());  // with its length: "save\0x" is not "save"
  const bool found = lua_rawget(L, -2) != LUA_TNIL;
  lua_replace(L, -3);  // the method (or nil) where the metatable was
  lua_pop(L, 1);       // __methods
  if (!found) lua_pop(L, 1);
  return found;
}

void push_subtable(lua_State* L, int torte_index, const char* name) {
  if (lua_getfield(L, torte_index, name) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, torte_index, name);
  }
}

}  // namespace torte::lua
