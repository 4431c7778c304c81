// torte.data, the binary-data library the Minecraft loader is written with: zlib/gzip, NBT, bit fields, file
// access, int16 maps, LZ4 blocks and xxHash32, through the built binary (TORTE_BINARY).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "minecraft_support.h"

namespace fs = std::filesystem;
using namespace torte::test;
using namespace torte::test::minecraft;

// ---- torte.data -------------------------------------------------------------------------------------------------

TEST_CASE("minecraft data: inflate and gunzip decode Python-made streams and reject bad ones", "[minecraft]") {
  McDir dir("inflate");
  // zlib.compress(b'hello torte! ' * 20, 9) and gzip.compress(same, 9, mtime=0), from Python 3.11.
  run_ok(dir, R"LUA(
local D = torte.data
local plain = ("hello torte! "):rep(20)
local z = "\x78\xda\xcb\x48\xcd\xc9\xc9\x57\x28\xc9\x2f\x2a\x49\x55\x54\xc8\x18\x99\x1c\x00\x7f\x97\x5c\xbd"
local g = "\x1f\x8b\x08\x00\x00\x00\x00\x00\x02\x03\xcb\x48\xcd\xc9\xc9\x57\x28\xc9\x2f\x2a\x49\x55\x54\xc8\x18"
          .. "\x99\x1c\x00\xd3\xad\x62\x57\x04\x01\x00\x00"
assert(D.inflate(z) == plain, "zlib")
assert(D.gunzip(g) == plain, "gzip")
local function err(f, s)
  local ok, e = pcall(f, s)
  assert(not ok, "expected an error")
  return e
end
-- Truncated at every length: an error, naming the function, never a crash or a silent short result.
for n = 1, #z - 1 do
  local e = err(D.inflate, z:sub(1, n))
  assert(e:find("torte.data.inflate", 1, true) and (e:find("truncated") or e:find("corrupt")), e)
end
for n = 1, #g - 1 do
  local e = err(D.gunzip, g:sub(1, n))
  assert(e:find("torte.data.gunzip", 1, true) and (e:find("truncated") or e:find("corrupt")), e)
end
assert(err(D.inflate, z:sub(1, 12)):find("truncated input"), "mid-stream cut says truncated")
-- Corrupt: a wrong checksum, a bad header, gzip data given to inflate, trailing bytes, empty input.
local bad = z:sub(1, -2) .. string.char((z:byte(-1) + 1) % 256)
assert(err(D.inflate, bad):find("corrupt input"), "checksum")
assert(err(D.inflate, "\x78\x9d" .. z:sub(3)):find("corrupt input"), "header")
assert(err(D.inflate, g):find("corrupt input"), "gzip is not zlib")
assert(err(D.inflate, z .. "xx"):find("2 bytes of trailing data"), "trailing")
assert(err(D.gunzip, ""):find("empty input"), "empty")
assert(err(D.inflate, 42):find("expects a string"), "type")
print("ok")
)LUA");
}

TEST_CASE("minecraft data: nbt decodes every tag type of a hand-made payload", "[minecraft]") {
  McDir dir("nbt_tags");
  run_ok(dir, R"LUA(
local D = torte.data
local P = string.pack
local function name(s) return P(">s2", s) end
local function tag(t, n, payload) return P("B", t) .. name(n) .. payload end
-- A compound with every tag type 1..12, nested lists and compounds, an empty list of TAG_End, and extremes.
local inner = tag(8, "s", P(">s2", "nested")) .. "\0"
local payload =
  tag(1, "byte", P(">i1", -128)) .. tag(2, "short", P(">i2", -32768)) .. tag(3, "int", P(">i4", -2147483648)) ..
  tag(4, "long", P(">i8", math.mininteger)) .. tag(4, "long2", P(">i8", math.maxinteger)) ..
  tag(5, "float", P(">f", 1.5)) .. tag(6, "double", P(">d", -0.1)) ..
  tag(7, "bytes", P(">i4", 4) .. "\0\1\255\128") .. tag(8, "string", P(">s2", "h\xc3\xa9llo")) ..
  tag(9, "list", P(">Bi4", 3, 3) .. P(">i4i4i4", 1, -2, 3)) ..
  tag(9, "empty", P(">Bi4", 0, 0)) ..
  tag(9, "compounds", P(">Bi4", 10, 2) .. inner .. inner) ..
  tag(9, "lists", P(">Bi4", 9, 1) .. P(">Bi4", 1, 2) .. P(">i1i1", 7, -7)) ..
  tag(10, "compound", inner) ..
  tag(11, "ints", P(">i4", 3) .. P(">i4i4i4", 2147483647, -1, 0)) ..
  tag(12, "longs", P(">i4", 3) .. P(">i8i8i8", math.mininteger, -1, 0x0123456789abcdef)) ..
  tag(12, "nolongs", P(">i4", 0)) ..
  "\0"
local s = tag(10, "root", payload)
local v, n, next = D.nbt(s)
assert(n == "root" and next == #s + 1, "name and end offset")
assert(v.byte == -128 and math.type(v.byte) == "integer")
assert(v.short == -32768 and v.int == -2147483648)
assert(v.long == math.mininteger and v.long2 == math.maxinteger)
assert(v.float == 1.5 and v.double == -0.1)
assert(v.bytes == "\0\1\255\128")
assert(v.string == "h\xc3\xa9llo")
assert(#v.list == 3 and v.list[2] == -2)
assert(type(v.empty) == "table" and #v.empty == 0)
assert(v.compounds[2].s == "nested" and v.compound.s == "nested")
assert(v.lists[1][2] == -7)
assert(#v.ints == 3 and v.ints[1] == 2147483647 and v.ints[2] == -1)
assert(#v.longs == 3 and v.longs[1] == math.mininteger and v.longs[2] == -1 and v.longs[3] == 0x0123456789abcdef)
assert(v.longs[4] == nil and v.longs[0] == nil)
local t = v.longs:table()
assert(#t == 3 and t[3] == 0x0123456789abcdef)
assert(tostring(v.longs):find("3 longs"))
assert(#v.nolongs == 0)
-- An offset: two root tags back to back.
local two = tag(3, "a", P(">i4", 5)) .. tag(8, "b", P(">s2", "x"))
local a, an, at = D.nbt(two)
local b, bn, bt = D.nbt(two, at)
assert(a == 5 and an == "a" and b == "x" and bn == "b" and bt == #two + 1)
-- Truncated at every length: the error says truncated (or names the bad tag) and where.
for cut = 0, #s - 1 do
  local ok, e = pcall(D.nbt, s:sub(1, cut))
  assert(not ok, "cut " .. cut .. " must fail")
  assert(e:find("torte.data.nbt: ", 1, true) and e:find("truncated input", 1, true), e)
end
local ok, e = pcall(D.nbt, s:sub(1, 40))
assert(e:find("a tag name needs 4 bytes, 2 left in 'root' at byte 39 of 40", 1, true), e)
ok, e = pcall(D.nbt, s:sub(1, 90))
assert(e:find("in 'root.double'", 1, true), e)
ok, e = pcall(D.nbt, tag(10, "r", tag(12, "longs", P(">i4", 100) .. ("\0"):rep(16)) .. "\0"))
assert(e:find("long array of 100 entries needs 800 bytes, 17 left", 1, true) and e:find("'r.longs'", 1, true), e)
ok, e = pcall(D.nbt, tag(10, "r", tag(13, "x", "") .. "\0"))
assert(e:find("unknown tag type 13", 1, true), e)
ok, e = pcall(D.nbt, tag(10, "r", tag(9, "l", P(">Bi4", 3, -1)) .. "\0"))
assert(e:find("negative list length", 1, true), e)
ok, e = pcall(D.nbt, tag(10, "r", tag(9, "l", P(">Bi4", 10, 2) .. "\0" .. tag(3, "x", P(">i2", 1)))))
assert(e:find("an int needs 4 bytes, 2 left in 'r.l[2].x'", 1, true), e)
ok, e = pcall(D.nbt, ("\10\0\0"):rep(600))
assert(e:find("deeper than 512", 1, true) or e:find("truncated"), e)
ok, e = pcall(D.nbt, "")
assert(e:find("truncated input", 1, true), e)
ok, e = pcall(D.nbt, s, #s + 5)
assert(e:find("outside the string", 1, true), e)
print("ok")
)LUA");
}

TEST_CASE("minecraft data: unpack_bits reads spanning and padded fields, maps and counts", "[minecraft]") {
  McDir dir("unpack");
  run_ok(dir, R"LUA(
local D = torte.data
local P = string.pack
-- Build a long array through NBT: 5-bit fields 0..(n-1) mod 32, spanning longs (pre-1.16) and padded (1.16+).
local function longs(values)
  local s = P("B", 12) .. P(">s2", "a") .. P(">i4", #values)
  for _, v in ipairs(values) do s = s .. P(">i8", v) end
  return (D.nbt(s))
end
local function pack(fields, bits, padded)
  local out, cur, used = {}, 0, 0
  local per = padded and 64 // bits or nil
  for i, f in ipairs(fields) do
    if padded then
      local k = (i - 1) % per
      cur = cur | (f << (k * bits))
      if k == per - 1 or i == #fields then out[#out + 1] = cur; cur = 0 end
    else
      for b = 0, bits - 1 do
        if (f >> b) & 1 == 1 then cur = cur | (1 << used) end
        used = used + 1
        if used == 64 then out[#out + 1] = cur; cur = 0; used = 0 end
      end
    end
  end
  if not padded and used > 0 then out[#out + 1] = cur end
  return out
end
local fields = {}
for i = 1, 4096 do fields[i] = (i * 7) % 32 end
for _, padded in ipairs({false, true}) do
  local a = longs(pack(fields, 5, padded))
  assert(#a == (padded and 342 or 320), #a)
  local s, counts = D.unpack_bits(a, 5, 4096, padded)
  assert(#s == 8192)
  for i = 1, 4096 do assert(string.unpack("<i2", s, 2 * i - 1) == fields[i], i) end
  local total = 0
  for v = 1, #counts do total = total + counts[v] end
  assert(total == 4096 and counts[1] == 128, "counts")
  -- A map: value v -> 100 - v (negative ids too).
  local map = {}
  for v = 0, 31 do map[v + 1] = 100 - 10 * v end
  local m = a:unpack_bits(5, 4096, padded, map)
  for i = 1, 4096 do assert(string.unpack("<i2", m, 2 * i - 1) == 100 - 10 * fields[i]) end
end
-- Strings are little-endian bit streams: nibbles low first.
local s = D.unpack_bits("\x21\x43", 4, 4)
assert(s == P("<i2i2i2i2", 1, 2, 3, 4))
assert(D.unpack_bits("\xff", 8, 1) == P("<i2", 255))
-- Errors.
local ok, e = pcall(D.unpack_bits, longs({1, 2}), 5, 4096)
assert(not ok and e:find("need 320 longs, got 2", 1, true), e)
ok, e = pcall(D.unpack_bits, {}, 5, 10)
assert(not ok and e:find("expects a string or a torte.data.longs", 1, true), e)
ok, e = pcall(D.unpack_bits, "\xff\xff\xff", 20, 1)
assert(not ok and e:find("does not fit int16", 1, true), e)
print("ok")
)LUA");
}

TEST_CASE("minecraft data: read_file and list_dir name the file they cannot read", "[minecraft]") {
  McDir dir("files");
  dir.write("a.bin", std::string("x\0y", 3));
  fs::create_directories(dir.path / "sub");
  dir.write("sub/r.0.0.mca", "");
  run_ok(dir, R"LUA(
local D = torte.data
assert(D.read_file("a.bin") == "x\0y")
local ok, e = pcall(D.read_file, "missing.mca")
assert(not ok and e:find("cannot open 'missing.mca'", 1, true), e)
local names = D.list_dir("sub")
assert(#names == 1 and names[1] == "r.0.0.mca")
local none, msg = D.list_dir("nowhere")
assert(none == nil and msg:find("nowhere"))
-- An empty region file holds no chunks.
local region = require "minecraft.region"
local r = region.open("sub/r.0.0.mca")
assert(#r:chunks() == 0 and r.rx == 0 and r.rz == 0)
print("ok")
)LUA");
}

TEST_CASE("minecraft data: map_int16 replaces int16 values, per value or through a selector", "[minecraft]") {
  McDir dir("map_int16");
  run_ok(dir, R"LUA(
local D = torte.data
local P = string.pack
local s = P("<i2i2i2i2i2", 1, -5, 7, 1, 32767)
assert(D.map_int16(s, {[1] = 2, [32767] = -32768}) == P("<i2i2i2i2i2", 2, -5, 7, 2, -32768))
assert(D.map_int16(s, {}) == s)
-- A selector: value i goes through maps[select:byte(i) + 1]; a missing map leaves the value.
assert(D.map_int16(s, {{[1] = 10}, nil, {[1] = 30, [7] = 70}}, "\0\0\2\2\1") == P("<i2i2i2i2i2", 10, -5, 70, 30, 32767))
local function err(...)
  local ok, e = pcall(D.map_int16, ...)
  assert(not ok)
  return e
end
assert(err("abc", {}):find("odd length", 1, true))
assert(err(s, {[1] = 40000}):find("integers in [-32768, 32767]", 1, true))
assert(err(s, {{}}, "\0"):find("the selector has 1 bytes for 5 values", 1, true))
assert(err(s, 5):find("expects a table", 1, true))
print("ok")
)LUA");
}

// ---- LZ4 chunks (Minecraft 1.20.5+) -----------------------------------------------------------------------------

TEST_CASE("minecraft data: lz4_block, lz4_compress and xxhash32", "[minecraft]") {
  McDir dir("lz4");
  run_ok(dir, R"LUA(
local D = torte.data
-- XXH32 reference values (xxHash's own test vectors).
assert(D.xxhash32("") == 0x02CC5D05, ("%08x"):format(D.xxhash32("")))
assert(D.xxhash32("a") == 0x550D7456, ("%08x"):format(D.xxhash32("a")))
assert(D.xxhash32("abc") == 0x32D153FF, ("%08x"):format(D.xxhash32("abc")))
assert(D.xxhash32("Nobody inspects the spammish repetition") == 0xE2293B2F)
assert(D.xxhash32("xxabcxx", 0, 3, 5) == D.xxhash32("abc"), "a range")
assert(D.xxhash32("abc", 1) ~= D.xxhash32("abc"), "the seed matters")
-- A block written by hand from the LZ4 block format (no liblz4 involved): 3 literals "abc", a match at offset 3
-- of 20 bytes (overlapping: a run), then 5 final literals.
local block = "\x3f" .. "abc" .. "\x03\x00" .. "\x01" .. "\x50" .. "XYZWV"
local want = ("abc"):rep(7) .. "ab" .. "XYZWV"
assert(D.lz4_block(block, #want) == want)
assert(D.lz4_block("..." .. block .. "..", #want, 4, -3) == want, "a range")
-- Round trips through liblz4's compressor: text, runs, random bytes, empty.
local parts = {}
for i = 1, 3000 do parts[i] = string.char((i * 7919) % 251) end
for _, s in ipairs({("hello torte "):rep(500), ("\0"):rep(70000), table.concat(parts), "x", ""}) do
  local z = D.lz4_compress(s)
  assert(D.lz4_block(z, #s) == s, #s)
end
-- Errors: corrupt, truncated, wrong sizes.
local function err(...)
  local ok, e = pcall(D.lz4_block, ...)
  assert(not ok, "expected an error")
  return e
end
local z = D.lz4_compress(("hello torte "):rep(500))
assert(err(z, 6001):find("size mismatch: the block decompresses to 6000 bytes, expected 6001", 1, true), err(z, 6001))
assert(err(z, 5999):find("corrupt or truncated input", 1, true), err(z, 5999))
for cut = 1, #z - 1 do assert(err(z:sub(1, cut), 6000):find("torte.data.lz4_block: ", 1, true)) end
assert(err("\x3f" .. "abc" .. "\x09\x00\x01\x50XYZWV", 28):find("corrupt", 1, true), "offset before the start")
assert(err("", 5):find("empty input", 1, true))
assert(err(z, -1):find("decompressed size", 1, true))
assert(err(42, 1):find("expects a string", 1, true))
print("ok")
)LUA");
}
