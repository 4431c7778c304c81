#include "binding.h"

#include <cmath>

namespace torte::lua {

std::string type_name(lua_State* L, int idx) {
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

void KwArgs::finish() {
  std::string unknown;
  lua_pushnil(L_);
  while (lua_next(L_, index_) != 0) {
    lua_pop(L_, 1);  // value
    if (lua_type(L_, -1) != LUA_TSTRING) {
      lua_pop(L_, 1);
      throw Error(function_ + ": positional values are not accepted; pass key = value pairs");
    }
    const std::string key = lua_tostring(L_, -1);
    // The smallest unknown key, not the first lua_next gives: that order changes from run to run.
    if (!read_.count(key) && (unknown.empty() || key < unknown)) unknown = key;
  }
  if (unknown.empty()) return;
  std::string known;
  for (const std::string& k : read_) known += (known.empty() ? "" : ", ") + k;
  throw Error(function_ + ": unknown key '" + unknown + "' (accepted keys: " + known + ")");
}

void set_functions(lua_State* L, const luaL_Reg* functions) { luaL_setfuncs(L, functions, 0); }

void push_subtable(lua_State* L, int torte_index, const char* name) {
  if (lua_getfield(L, torte_index, name) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, torte_index, name);
  }
}

}  // namespace torte::lua
