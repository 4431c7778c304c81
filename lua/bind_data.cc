// torte.data.*: generic building blocks for reading binary data files from Lua (the Minecraft loader in
// lua/minecraft/ is written with them; nothing here knows about Minecraft).
//
//   local s = torte.data.read_file("r.0.0.mca")        -- the whole file as a string; errors name the file
//   local names = torte.data.list_dir("world/region")   -- sorted names, or nil + message
//   local raw = torte.data.inflate(s:sub(6, 5 + n) [, limit])   -- zlib stream -> string (gunzip for gzip)
//   local root, name, next = torte.data.nbt(raw [, offset=1])   -- NBT (big-endian) -> Lua values
//   local ids, counts = torte.data.unpack_bits(src, bits, count [, padded [, map]])
//   local s2 = torte.data.map_int16(s, {[v] = w, ...} [, nil]) / map_int16(s, {map1, map2, ...}, select)
//   torte.data.lz4_block, lz4_compress, xxhash32                 -- lua/bind_data_lz4.cc
//   torte.data.longs (NBT long arrays) and unpack_bits            -- lua/bind_data_longs.cc
//
// read_file takes regular files only, up to a quarter of the memory limit (core/file_read.h). inflate and gunzip
// stop with an error once the output would pass `limit` bytes (default kDefaultDecompressLimit, 256 MiB: a
// Minecraft chunk is a few MB), so a compression bomb costs at most that much. nbt checks every declared count
// against the bytes left (each entry's smallest encoding) and the memory budget before building a table.
//
// NBT tags become: byte/short/int/long -> integer, float/double -> number, string -> string, byte array ->
// string (raw bytes), list -> array table, compound -> table, int array -> integer array table, long array ->
// a compact `torte.data.longs` userdata (#a, a[i] with 1-based i, a:table(), a:unpack_bits(...)); block-state
// arrays are long arrays of thousands of entries and only ever read through unpack_bits.
//
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/file_read.h"
#include "core/memory_budget.h"
#include "core/text.h"
#include "file_access.h"
#include "types.h"

namespace torte::lua {

namespace {

// ---- files and compression ---------------------------------------------------------------------------------

// list_dir(path) -> sorted array of the names in a directory (nil, message when it cannot be read).
int l_list_dir(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error("torte.data.list_dir expects a directory name, got " + type_name(L, 1));
  const std::string path = lua_tostring(L, 1);
  check_read(L, path, "torte.data.list_dir");
  std::vector<std::string> names;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec))
    names.push_back(it->path().filename().string());
  if (ec) {
    lua_pushnil(L);
    lua_pushstring(L, ("torte.data.list_dir: cannot read '" + path + "': " + ec.message()).c_str());
    return 2;
  }
  std::sort(names.begin(), names.end());
  lua_createtable(L, int(names.size()), 0);
  for (size_t i = 0; i < names.size(); ++i) {
    lua_pushlstring(L, names[i].data(), names[i].size());
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  return 1;
}

// read_file(path): the whole file (a regular file within the size bound of core/file_read.h) as a string.
int l_read_file(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error("torte.data.read_file expects a file name, got " + type_name(L, 1));
  const std::string path = lua_tostring(L, 1);
  check_read(L, path, "torte.data.read_file");
  std::string data;
  try {
    data = read_file_bytes(path);
  } catch (const Error& e) {
    throw Error(std::string("torte.data.read_file: ") + e.what());
  }
  lua_pushlstring(L, data.data(), data.size());
  return 1;
}

// windowBits 15: zlib, 15 + 16: gzip. Decompresses one stream of at most `limit` bytes; trailing bytes after it
// are an error.
std::string decompress(const char* fn, const unsigned char* in, size_t n, int window_bits, uint64_t limit) {
  z_stream z{};
  if (inflateInit2(&z, window_bits) != Z_OK) throw Error(std::string(fn) + ": cannot initialise zlib");
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end{&z};
  std::string out;
  // A first guess of 4x the input; growth doubles, never past the limit (+1 byte, to tell "exactly the limit"
  // from "more").
  const uint64_t cap = limit + 1;
  out.resize(size_t(std::min<uint64_t>(cap, n < 64 ? 256 : uint64_t(n) * 4)));
  z.next_in = const_cast<unsigned char*>(in);
  auto over_limit = [&] {
    return Error(std::string(fn) + ": the stream decompresses to more than " + format_bytes(limit) +
                 " (the output limit; pass a larger one as the second argument) after " +
                 std::to_string(z.total_in) + " of " + std::to_string(n) + " input bytes");
  };
  int rc = Z_OK;
  size_t fed = 0;  // input bytes handed to zlib so far (avail_in is 32 bits)
  for (;;) {
    if (z.avail_in == 0 && fed < n) {
      const size_t chunk = std::min<size_t>(n - fed, 1u << 30);
      z.next_in = const_cast<unsigned char*>(in) + fed;
      z.avail_in = uInt(chunk);
      fed += chunk;
    }
    if (z.total_out == out.size()) {
      if (out.size() >= cap) throw over_limit();
      const uint64_t grown = std::min<uint64_t>(cap, 2 * uint64_t(out.size()));
      reserve_memory(grown, std::string(fn) + " output");
      out.resize(size_t(grown));
    }
    z.next_out = reinterpret_cast<unsigned char*>(out.data()) + z.total_out;
    z.avail_out = uInt(std::min<uint64_t>(out.size() - z.total_out, 1u << 30));
    rc = inflate(&z, Z_NO_FLUSH);
    if (z.total_out > limit) throw over_limit();
    if (rc == Z_STREAM_END) break;
    if (rc == Z_OK) continue;
    if (rc == Z_BUF_ERROR && z.avail_out > 0) {  // no progress possible: the input ran out
      throw Error(std::string(fn) + ": truncated input: the compressed stream ends early (all " +
                  std::to_string(z.total_in) + " bytes read, " + std::to_string(z.total_out) +
                  " bytes decompressed)");
    }
    if (rc == Z_BUF_ERROR) continue;
    const std::string msg = z.msg ? z.msg : "error " + std::to_string(rc);
    throw Error(std::string(fn) + ": corrupt input near byte " + std::to_string(z.total_in) + ": " + msg);
  }
  const size_t used = z.total_in, produced = z.total_out;
  out.resize(produced);
  if (used != n)
    throw Error(std::string(fn) + ": " + std::to_string(n - used) + " bytes of trailing data after the stream");
  return out;
}

// inflate(s [, limit]) / gunzip(s [, limit]): limit = the most bytes the output may have (kDefaultDecompressLimit).
template <int WindowBits>
int l_decompress(lua_State* L) {
  const char* fn = WindowBits == 15 ? "torte.data.inflate" : "torte.data.gunzip";
  if (lua_type(L, 1) != LUA_TSTRING) throw Error(std::string(fn) + " expects a string, got " + type_name(L, 1));
  size_t n = 0;
  const char* s = lua_tolstring(L, 1, &n);
  const uint64_t limit = decompress_limit(L, 2, fn);
  if (n == 0) throw Error(std::string(fn) + ": empty input");
  const std::string out = decompress(fn, reinterpret_cast<const unsigned char*>(s), n, WindowBits, limit);
  lua_pushlstring(L, out.data(), out.size());
  return 1;
}

// ---- NBT -----------------------------------------------------------------------------------------------------

// "[i]" for error paths (built by appending: GCC 12 warns falsely about "[" + std::to_string(i) + "]").
std::string index_label(size_t i) {
  std::string s(1, '[');
  s += std::to_string(i);
  s += ']';
  return s;
}

class NbtReader {
 public:
  NbtReader(lua_State* L, const unsigned char* data, size_t size, size_t pos) : L_(L), d_(data), n_(size), p_(pos) {}

  // Reads a named root tag; pushes its value and name. Returns the position after it.
  size_t root() {
    need(1, "the root tag type");
    const int type = d_[p_++];
    if (type == 0) fail("the root tag is TAG_End (empty input?)");
    if (type > 12) fail("unknown root tag type " + std::to_string(type));
    std::string name = read_name();
    path_.push_back(name.empty() ? std::string("<root>") : name);
    value(type);
    path_.pop_back();
    lua_pushlstring(L_, name.data(), name.size());
    return p_;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    std::string where;
    for (const std::string& s : path_) {
      if (!where.empty() && s[0] != '[') where += '.';
      where += s;
    }
    // Tag names come from the file: control bytes would break the one-line error.
    throw Error("torte.data.nbt: " + what + (where.empty() ? "" : " in '" + escape_text(where) + "'") + " at byte " +
                std::to_string(p_ + 1) + " of " + std::to_string(n_));
  }
  void need(size_t bytes, const char* what) const {
    if (n_ - p_ < bytes)
      fail(std::string("truncated input: ") + what + " needs " + std::to_string(bytes) + " bytes, " +
           std::to_string(n_ - p_) + " left");
  }
  uint64_t be(int bytes) {
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | d_[p_ + i];
    p_ += bytes;
    return v;
  }
  std::string read_name() {
    need(2, "a tag name length");
    const size_t len = size_t(be(2));
    need(len, "a tag name");
    std::string s(reinterpret_cast<const char*>(d_ + p_), len);
    p_ += len;
    return s;
  }
  size_t array_length(size_t element_bytes, const char* what) {
    need(4, "an array length");
    const int32_t len = int32_t(uint32_t(be(4)));
    if (len < 0) fail(std::string("negative ") + what + " length " + std::to_string(len));
    if ((n_ - p_) / element_bytes < size_t(len))
      fail(std::string("truncated input: ") + what + " of " + std::to_string(len) + " entries needs " +
           std::to_string(size_t(len) * element_bytes) + " bytes, " + std::to_string(n_ - p_) + " left");
    return size_t(len);
  }

  // What a Lua array of `len` entries of NBT type `type` costs: 16 bytes a slot (a TValue), plus a table (lists,
  // compounds, int arrays), a string or a userdata per entry, far more than the 1 to 8 bytes an entry can take in
  // NBT; so a short input cannot build tables the machine cannot hold.
  void reserve_table(size_t len, int type, const char* what) {
    static constexpr uint64_t kEntryBytes[13] = {16, 16, 16, 16, 16, 16, 16, 48, 48, 80, 80, 80, 48};
    try {
      reserve_memory(uint64_t(len) * kEntryBytes[type],
                     "an NBT " + std::string(what) + " of " + std::to_string(len) + " entries");
    } catch (const Error& e) {
      fail(e.what());
    }
  }

  void value(int type) {
    if (++depth_ > 512) fail("nesting deeper than 512 levels");
    luaL_checkstack(L_, 8, "torte.data.nbt");
    switch (type) {
      case 1:
        need(1, "a byte");
        lua_pushinteger(L_, int8_t(be(1)));
        break;
      case 2:
        need(2, "a short");
        lua_pushinteger(L_, int16_t(be(2)));
        break;
      case 3:
        need(4, "an int");
        lua_pushinteger(L_, int32_t(uint32_t(be(4))));
        break;
      case 4:
        need(8, "a long");
        lua_pushinteger(L_, lua_Integer(be(8)));
        break;
      case 5: {
        need(4, "a float");
        const uint32_t bits = uint32_t(be(4));
        float f;
        std::memcpy(&f, &bits, 4);
        lua_pushnumber(L_, f);
        break;
      }
      case 6: {
        need(8, "a double");
        const uint64_t bits = be(8);
        double f;
        std::memcpy(&f, &bits, 8);
        lua_pushnumber(L_, f);
        break;
      }
      case 7: {
        const size_t len = array_length(1, "byte array");
        lua_pushlstring(L_, reinterpret_cast<const char*>(d_ + p_), len);
        p_ += len;
        break;
      }
      case 8: {
        need(2, "a string length");
        const size_t len = size_t(be(2));
        need(len, "a string");
        lua_pushlstring(L_, reinterpret_cast<const char*>(d_ + p_), len);
        p_ += len;
        break;
      }
      case 9: {
        need(1, "a list element type");
        const int et = d_[p_++];
        if (et > 12) fail("unknown list element type " + std::to_string(et));
        // The fewest bytes an entry of each type takes (a compound: its TAG_End; arrays and strings: their length).
        static constexpr size_t kMinBytes[13] = {1, 1, 2, 4, 8, 4, 8, 4, 2, 5, 1, 4, 4};
        const size_t len = array_length(kMinBytes[et], "list");
        if (et == 0 && len > 0) fail("a list of TAG_End with " + std::to_string(len) + " entries");
        reserve_table(len, et, "list");
        lua_createtable(L_, int(len), 0);
        for (size_t i = 0; i < len; ++i) {
          path_.push_back(index_label(i + 1));
          value(et);
          path_.pop_back();
          lua_rawseti(L_, -2, lua_Integer(i + 1));
        }
        break;
      }
      case 10: {
        lua_newtable(L_);
        for (;;) {
          need(1, "a tag type (compound not closed by TAG_End)");
          const int t = d_[p_++];
          if (t == 0) break;
          if (t > 12) fail("unknown tag type " + std::to_string(t));
          std::string name = read_name();
          lua_pushlstring(L_, name.data(), name.size());
          path_.push_back(std::move(name));
          value(t);
          path_.pop_back();
          lua_rawset(L_, -3);
        }
        break;
      }
      case 11: {
        const size_t len = array_length(4, "int array");
        reserve_table(len, 3, "int array");
        lua_createtable(L_, int(len), 0);
        for (size_t i = 0; i < len; ++i) {
          lua_pushinteger(L_, int32_t(uint32_t(be(4))));
          lua_rawseti(L_, -2, lua_Integer(i + 1));
        }
        break;
      }
      case 12: {
        const size_t len = array_length(8, "long array");
        int64_t* v = new_longs(L_, len);
        for (size_t i = 0; i < len; ++i) v[i] = int64_t(be(8));
        break;
      }
      default:
        fail(std::string("unexpected tag type ") + std::to_string(type));
    }
    --depth_;
  }

  lua_State* L_;
  const unsigned char* d_;
  size_t n_, p_;
  int depth_ = 0;
  std::vector<std::string> path_;
};

// nbt(s [, offset = 1]) -> value, name, next_offset
int l_nbt(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error("torte.data.nbt expects a string, got " + type_name(L, 1));
  size_t n = 0;
  const char* s = lua_tolstring(L, 1, &n);
  const lua_Integer offset = luaL_optinteger(L, 2, 1);
  if (offset < 1 || size_t(offset) > n + 1)
    throw Error("torte.data.nbt: offset " + std::to_string(offset) + " is outside the string (length " +
                std::to_string(n) + ")");
  lua_settop(L, 2);
  NbtReader r(L, reinterpret_cast<const unsigned char*>(s), n, size_t(offset - 1));
  const size_t end = r.root();
  lua_pushinteger(L, lua_Integer(end + 1));
  return 3;
}

// ---- int16 arrays -----------------------------------------------------------------------------------------

// A value -> value table read from the Lua table at `idx` (integer keys and values in int16 range).
std::vector<std::pair<int32_t, int32_t>> int16_map(lua_State* L, int idx, const char* fn) {
  std::vector<std::pair<int32_t, int32_t>> m;
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    int ok1 = 0, ok2 = 0;
    const lua_Integer k = lua_tointegerx(L, -2, &ok1), v = lua_tointegerx(L, -1, &ok2);
    if (!ok1 || !ok2 || k < -32768 || k > 32767 || v < -32768 || v > 32767)
      throw Error(std::string(fn) + ": map entries must be integers in [-32768, 32767]");
    m.emplace_back(int32_t(k), int32_t(v));
    lua_pop(L, 1);
  }
  std::sort(m.begin(), m.end());
  return m;
}

// map_int16(s, map) or map_int16(s, maps, select): a copy of `s` (little-endian int16 values) with every value v
// that is a key of the map replaced by map[v]. With `select` (a string of one byte per value), value i uses
// maps[select:byte(i) + 1] (a missing map leaves the value).
int l_map_int16(lua_State* L) {
  const char* fn = "torte.data.map_int16";
  if (lua_type(L, 1) != LUA_TSTRING) throw Error(std::string(fn) + " expects a string, got " + type_name(L, 1));
  size_t n = 0;
  const char* s = lua_tolstring(L, 1, &n);
  if (n % 2) throw Error(std::string(fn) + ": the string has an odd length (" + std::to_string(n) + ")");
  if (lua_type(L, 2) != LUA_TTABLE) throw Error(std::string(fn) + " expects a table as argument 2");
  std::vector<std::vector<std::pair<int32_t, int32_t>>> maps;
  const unsigned char* select = nullptr;
  if (lua_isnoneornil(L, 3)) {
    maps.push_back(int16_map(L, 2, fn));
  } else {
    if (lua_type(L, 3) != LUA_TSTRING) throw Error(std::string(fn) + ": the selector must be a string");
    size_t ns = 0;
    select = reinterpret_cast<const unsigned char*>(lua_tolstring(L, 3, &ns));
    if (ns != n / 2)
      throw Error(std::string(fn) + ": the selector has " + std::to_string(ns) + " bytes for " +
                  std::to_string(n / 2) + " values");
    for (int k = 1; k <= 256; ++k) {
      if (lua_geti(L, 2, k) == LUA_TTABLE) {
        maps.resize(size_t(k));
        maps[size_t(k - 1)] = int16_map(L, lua_gettop(L), fn);
      }
      lua_pop(L, 1);
    }
  }
  std::string out(s, n);
  for (size_t i = 0; i < n / 2; ++i) {
    const size_t k = select ? select[i] : 0;
    if (k >= maps.size() || maps[k].empty()) continue;
    const auto& m = maps[k];
    const int32_t v = int16_t(uint16_t(uint8_t(out[2 * i])) | uint16_t(uint8_t(out[2 * i + 1]) << 8));
    auto it = std::lower_bound(m.begin(), m.end(), std::make_pair(v, INT32_MIN));
    if (it == m.end() || it->first != v) continue;
    out[2 * i] = char(uint32_t(it->second) & 0xff);
    out[2 * i + 1] = char((uint32_t(it->second) >> 8) & 0xff);
  }
  lua_pushlstring(L, out.data(), out.size());
  return 1;
}

}  // namespace

uint64_t decompress_limit(lua_State* L, int idx, const char* fn) {
  if (lua_isnoneornil(L, idx)) return kDefaultDecompressLimit;
  int ok = 0;
  const lua_Integer v = lua_tointegerx(L, idx, &ok);
  if (!ok || v < 0)
    throw Error(std::string(fn) + ": the output limit must be a non-negative integer (bytes), got " +
                (ok ? std::to_string(v) : type_name(L, idx)));
  return uint64_t(v);
}

void open_data(lua_State* L, int torte_index) {
  const luaL_Reg fns[] = {{"read_file", guarded<l_read_file>},
                          {"list_dir", guarded<l_list_dir>},
                          {"inflate", guarded<l_decompress<15>>},
                          {"gunzip", guarded<l_decompress<15 + 16>>},
                          {"nbt", guarded<l_nbt>},
                          {"map_int16", guarded<l_map_int16>},
                          {nullptr, nullptr}};
  push_subtable(L, torte_index, "data");
  set_functions(L, fns);
  set_data_longs_functions(L);  // lua/bind_data_longs.cc
  set_data_lz4_functions(L);    // lua/bind_data_lz4.cc
  lua_pop(L, 1);
}

}  // namespace torte::lua
