// torte.data's LZ4 and xxHash functions (Minecraft 1.20.5+ stores chunks as LZ4Block streams, whose block
// headers carry an XXH32 checksum): Debian's liblz4 and libxxhash under the string-range conventions of
// torte.data (see lua/bind_data.cc for the whole library).
//
//   local raw = torte.data.lz4_block(s, decompressed_size [, i [, j]])   -- one raw LZ4 block (liblz4), s:sub(i, j)
//     (a size over 255x the block's bytes is refused as corrupt before anything is allocated)
//   local z = torte.data.lz4_compress(s [, i [, j]])     -- one raw LZ4 block (LZ4_compress_default)
//   local h = torte.data.xxhash32(s [, seed=0 [, i [, j]]])   -- XXH32 of s:sub(i, j), an integer in [0, 2^32)
#include <lz4.h>
#include <xxhash.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/memory_budget.h"
#include "types.h"

namespace torte::lua {

namespace {

// The byte range [i, j] (1-based, inclusive, like string.sub; negative counts from the end) of the string at 1.
std::string_view string_range(lua_State* L, const char* fn, int i_idx) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error(std::string(fn) + " expects a string, got " + type_name(L, 1));
  size_t n = 0;
  const char* s = lua_tolstring(L, 1, &n);
  auto index = [&](int idx, lua_Integer def) -> lua_Integer {
    if (lua_isnoneornil(L, idx)) return def;
    int ok = 0;
    const lua_Integer v = lua_tointegerx(L, idx, &ok);
    if (!ok) throw Error(std::string(fn) + ": argument " + std::to_string(idx) + " must be an integer");
    return v < 0 ? lua_Integer(n) + v + 1 : v;
  };
  lua_Integer i = index(i_idx, 1), j = index(i_idx + 1, lua_Integer(n));
  if (i < 1) i = 1;
  if (j > lua_Integer(n)) j = lua_Integer(n);
  if (i > j) return {};
  return {s + (i - 1), size_t(j - i + 1)};
}

// lz4_block(s, size [, i [, j]]): decompresses one raw LZ4 block (no frame) that must give exactly `size` bytes.
int l_lz4_block(lua_State* L) {
  const char* fn = "torte.data.lz4_block";
  int ok = 0;
  const lua_Integer size = lua_tointegerx(L, 2, &ok);
  if (!ok || size < 0 || size > 0x7fffffff)
    throw Error(std::string(fn) + ": the decompressed size must be an integer in [0, 2^31), got " +
                (lua_isnoneornil(L, 2) ? std::string("nothing") : std::string(luaL_tolstring(L, 2, nullptr))));
  const std::string_view in = string_range(L, fn, 3);
  if (in.size() > size_t(LZ4_MAX_INPUT_SIZE)) throw Error(std::string(fn) + ": input too large");
  if (in.empty()) {
    if (size == 0) {
      lua_pushliteral(L, "");
      return 1;
    }
    throw Error(std::string(fn) + ": empty input for " + std::to_string(size) + " bytes");
  }
  // A block cannot decode to more than 255 bytes per input byte (each length byte adds at most 255): a larger
  // size is corrupt, and is refused before the output is allocated.
  if (uint64_t(size) > 255 * uint64_t(in.size()) + 15)
    throw Error(std::string(fn) + ": corrupt input: " + std::to_string(in.size()) + " bytes cannot decode to " +
                std::to_string(size) + " bytes (an LZ4 block expands 255-fold at most)");
  reserve_memory(uint64_t(size), std::string(fn) + " output");
  std::string out(size_t(size), '\0');
  // LZ4_decompress_safe never reads or writes out of bounds; a negative result is a malformed or truncated block,
  // or one that would decompress to more than `size` bytes.
  const int got = LZ4_decompress_safe(in.data(), out.data(), int(in.size()), int(size));
  if (got < 0)
    throw Error(std::string(fn) + ": corrupt or truncated input (" + std::to_string(in.size()) +
                " bytes do not decode as an LZ4 block of " + std::to_string(size) + " bytes, error at input byte " +
                std::to_string(-got) + ")");
  if (got != size)
    throw Error(std::string(fn) + ": size mismatch: the block decompresses to " + std::to_string(got) +
                " bytes, expected " + std::to_string(size));
  lua_pushlstring(L, out.data(), out.size());
  return 1;
}

// lz4_compress(s [, i [, j]]): one raw LZ4 block (for tests and writers).
int l_lz4_compress(lua_State* L) {
  const char* fn = "torte.data.lz4_compress";
  const std::string_view in = string_range(L, fn, 2);
  if (in.size() > size_t(LZ4_MAX_INPUT_SIZE)) throw Error(std::string(fn) + ": input too large");
  std::string out(size_t(LZ4_compressBound(int(in.size()))), '\0');
  const int n = LZ4_compress_default(in.data(), out.data(), int(in.size()), int(out.size()));
  if (n <= 0 && !in.empty()) throw Error(std::string(fn) + ": compression failed");
  lua_pushlstring(L, out.data(), size_t(std::max(n, 0)));
  return 1;
}

// xxhash32(s [, seed [, i [, j]]]) -> integer in [0, 2^32).
int l_xxhash32(lua_State* L) {
  const char* fn = "torte.data.xxhash32";
  lua_Integer seed = 0;
  if (!lua_isnoneornil(L, 2)) {
    int ok = 0;
    seed = lua_tointegerx(L, 2, &ok);
    if (!ok) throw Error(std::string(fn) + ": the seed must be an integer");
  }
  const std::string_view in = string_range(L, fn, 3);
  lua_pushinteger(L, lua_Integer(XXH32(in.data(), in.size(), XXH32_hash_t(uint64_t(seed) & 0xffffffffu))));
  return 1;
}

}  // namespace

void set_data_lz4_functions(lua_State* L) {
  const luaL_Reg fns[] = {{"lz4_block", guarded<l_lz4_block>},
                          {"lz4_compress", guarded<l_lz4_compress>},
                          {"xxhash32", guarded<l_xxhash32>},
                          {nullptr, nullptr}};
  set_functions(L, fns);
}

}  // namespace torte::lua
