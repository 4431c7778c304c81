// torte.data.longs, the compact userdata an NBT long array becomes (#a, a[i] with 1-based i, a:table(),
// a:unpack_bits(...)), and torte.data.unpack_bits, which reads the bit-packed fields of one (or of a string).
// See lua/bind_data.cc for the whole library.
//
// unpack_bits reads `count` unsigned `bits`-wide fields from `src` (a torte.data.longs, or a string read as
// little-endian bytes), least significant bits first. Fields span unit boundaries unless `padded` is true, in
// which case each 64-bit long (or byte, for strings) holds floor(64 / bits) fields and the rest is padding.
// It returns a string of `count` little-endian int16 values -- the fields themselves, or map[field + 1] when a
// `map` table is given (missing entries are 0) -- and a table counting how often each field value occurred
// (counts[v + 1]).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "types.h"

namespace torte::lua {

namespace {

constexpr const char* kLongsName = "torte.data.longs";

// ---- long arrays ---------------------------------------------------------------------------------------------

struct Longs {
  UserdataHeader header;  // its type is in its bytes, so debug.setmetatable cannot pass another userdata off as one
  lua_Integer n;
  int64_t v[1];  // n entries follow
};

Longs* check_longs(lua_State* L, int idx, const char* fn) {
  auto* a = reinterpret_cast<Longs*>(tagged_userdata(L, idx, &TypeTag<Longs>::id));
  if (!a) throw Error(std::string(fn) + " expects a " + kLongsName + ", got " + type_name(L, idx));
  return a;
}

int l_unpack_bits(lua_State* L);  // below; a method of longs as well as torte.data.unpack_bits
int longs_table(lua_State* L) {
  Longs* a = check_longs(L, 1, "torte.data.longs:table");
  lua_createtable(L, int(a->n), 0);
  for (lua_Integer i = 0; i < a->n; ++i) {
    lua_pushinteger(L, a->v[i]);
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

int longs_index(lua_State* L) {
  Longs* a = check_longs(L, 1, "index");
  if (lua_type(L, 2) == LUA_TNUMBER) {
    int ok = 0;
    const lua_Integer i = lua_tointegerx(L, 2, &ok);
    if (ok && i >= 1 && i <= a->n)
      lua_pushinteger(L, a->v[i - 1]);
    else
      lua_pushnil(L);
    return 1;
  }
  const char* key = lua_tostring(L, 2);
  if (!key || !push_method(L, 1, key)) {
    throw Error(std::string(kLongsName) + " has no field '" + (key ? key : "?") +
                "' (index it with 1..#a; methods: table, unpack_bits)");
  }
  return 1;
}

int longs_len(lua_State* L) {
  lua_pushinteger(L, check_longs(L, 1, "#")->n);
  return 1;
}

int longs_tostring(lua_State* L) {
  lua_pushfstring(L, "%s (%I longs)", kLongsName, check_longs(L, 1, "tostring")->n);
  return 1;
}

// ---- bit fields ----------------------------------------------------------------------------------------------

// unpack_bits(src, bits, count [, padded [, map]]) -> int16 string, counts
int l_unpack_bits(lua_State* L) {
  const char* fn = "torte.data.unpack_bits";
  const int64_t* longs = nullptr;
  const unsigned char* bytes = nullptr;
  size_t units = 0;
  int unit_bits = 0;
  if (lua_type(L, 1) == LUA_TSTRING) {
    bytes = reinterpret_cast<const unsigned char*>(lua_tolstring(L, 1, &units));
    unit_bits = 8;
  } else if (auto* a = reinterpret_cast<Longs*>(tagged_userdata(L, 1, &TypeTag<Longs>::id))) {
    longs = a->v;
    units = size_t(a->n);
    unit_bits = 64;
  } else {
    throw Error(std::string(fn) + " expects a string or a " + kLongsName + ", got " + type_name(L, 1));
  }
  const lua_Integer bits = luaL_checkinteger(L, 2), count = luaL_checkinteger(L, 3);
  const bool padded = lua_toboolean(L, 4);
  if (bits < 1 || bits > 32) throw Error(std::string(fn) + ": bits must be in 1..32, got " + std::to_string(bits));
  if (count < 0 || count > (1 << 24)) throw Error(std::string(fn) + ": bad count " + std::to_string(count));
  if (padded && bits > unit_bits)
    throw Error(std::string(fn) + ": " + std::to_string(bits) + "-bit fields do not fit a padded " +
                std::to_string(unit_bits) + "-bit unit");
  const size_t per_unit = padded ? size_t(unit_bits / bits) : 0;
  const size_t needed = padded ? (size_t(count) + per_unit - 1) / per_unit
                               : (size_t(count) * size_t(bits) + size_t(unit_bits) - 1) / size_t(unit_bits);
  if (units < needed)
    throw Error(std::string(fn) + ": " + std::to_string(count) + (padded ? " padded " : " ") + std::to_string(bits) +
                "-bit fields need " + std::to_string(needed) + (longs ? " longs" : " bytes") + ", got " +
                std::to_string(units));
  const bool has_map = lua_istable(L, 5);
  std::vector<int32_t> map;
  if (has_map) {
    const lua_Integer m = luaL_len(L, 5);
    map.resize(size_t(m));
    for (lua_Integer i = 0; i < m; ++i) {
      lua_rawgeti(L, 5, i + 1);
      int ok = 0;
      const lua_Integer v = lua_tointegerx(L, -1, &ok);
      if (!ok && !lua_isnil(L, -1)) throw Error(std::string(fn) + ": map[" + std::to_string(i + 1) + "] is not an integer");
      if (v < -32768 || v > 32767)
        throw Error(std::string(fn) + ": map[" + std::to_string(i + 1) + "] = " + std::to_string(v) +
                    " does not fit 16 bits");
      map[size_t(i)] = int32_t(v);
      lua_pop(L, 1);
    }
  }
  const uint64_t mask = (uint64_t(1) << bits) - 1;
  auto unit = [&](size_t i) -> uint64_t { return longs ? uint64_t(longs[i]) : uint64_t(bytes[i]); };
  std::string out(size_t(count) * 2, '\0');
  std::vector<lua_Integer> counts;
  for (size_t k = 0; k < size_t(count); ++k) {
    uint64_t v;
    if (padded) {
      v = (unit(k / per_unit) >> ((k % per_unit) * size_t(bits))) & mask;
    } else {
      const size_t bit = k * size_t(bits), u = bit / size_t(unit_bits), sh = bit % size_t(unit_bits);
      v = unit(u) >> sh;
      for (size_t got = size_t(unit_bits) - sh, uu = u + 1; got < size_t(bits); got += size_t(unit_bits), ++uu)
        v |= unit(uu) << got;
      v &= mask;
    }
    if (v >= counts.size()) counts.resize(size_t(v) + 1, 0);
    ++counts[size_t(v)];
    int32_t o;
    if (has_map) {
      o = v < map.size() ? map[size_t(v)] : 0;
    } else {
      if (v > 32767)
        throw Error(std::string(fn) + ": field value " + std::to_string(v) + " does not fit int16 (give a map)");
      o = int32_t(v);
    }
    out[2 * k] = char(uint32_t(o) & 0xff);
    out[2 * k + 1] = char((uint32_t(o) >> 8) & 0xff);
  }
  lua_pushlstring(L, out.data(), out.size());
  lua_createtable(L, int(counts.size()), 0);
  for (size_t i = 0; i < counts.size(); ++i) {
    lua_pushinteger(L, counts[i]);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  return 2;
}

}  // namespace

int64_t* new_longs(lua_State* L, size_t n) {
  auto* a = static_cast<Longs*>(lua_newuserdatauv(L, offsetof(Longs, v) + sizeof(int64_t) * (n ? n : 1), 0));
  a->header = {UserdataHeader::kMagic, &TypeTag<Longs>::id, kLongsName, nullptr};
  a->n = lua_Integer(n);
  luaL_setmetatable(L, kLongsName);
  return a->v;
}

void set_data_longs_functions(lua_State* L) {
  luaL_newmetatable(L, kLongsName);
  lua_pushcfunction(L, collect_tagged);  // longs own nothing, but a scene given this metatable still must be freed
  lua_setfield(L, -2, "__gc");
  lua_pushcfunction(L, guarded<longs_index>);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, guarded<longs_len>);
  lua_setfield(L, -2, "__len");
  lua_pushcfunction(L, guarded<longs_tostring>);
  lua_setfield(L, -2, "__tostring");
  lua_pushstring(L, kLongsName);
  lua_setfield(L, -2, "__metatable");
  const luaL_Reg methods[] = {{"table", guarded<longs_table>}, {"unpack_bits", guarded<l_unpack_bits>}, {nullptr, nullptr}};
  set_methods(L, methods);
  lua_pop(L, 1);
  const luaL_Reg fns[] = {{"unpack_bits", guarded<l_unpack_bits>}, {nullptr, nullptr}};
  set_functions(L, fns);
}

}  // namespace torte::lua
