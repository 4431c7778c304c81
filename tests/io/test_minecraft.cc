// torte.data (files, zlib/gzip, NBT, bit fields) and the Minecraft loader in lua/minecraft/, end to end through the
// built binary (TORTE_BINARY).
//
// The expected per-world figures come from two independent sources:
//   * chunks / full chunks / DataVersion / non-air blocks: ../shared/data/SOURCES.md (its own checker);
//   * the same figures and the raw block at a few positions: scripts/mc_reference.py, a separate decoder in Python
//     (zlib + struct, no code shared with lua/ or bind_data.cc). The positions were picked once from sections the
//     Lua loader had loaded (non-air voxels at fixed offsets, plus neighbours), then decoded by the Python script:
//       python3 scripts/mc_reference.py ../shared/data/minecraft <world> x,y,z ...
//     Raw blocks are "minecraft:<name>" for palette formats and "<id>:<data>" before 1.13.
// The world tests skip (with a message) when ../shared/data is absent.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct McDir : TempDir {
  explicit McDir(const std::string& name) : TempDir("minecraft", name) {}
};

const fs::path kWorlds = fs::path(TORTE_SOURCE_DIR) / ".." / "shared" / "data" / "minecraft";

bool have_worlds() {
  if (fs::is_directory(kWorlds)) return true;
  WARN("skipped: " << kWorlds.string() << " is absent (../shared/data not installed)");
  return false;
}

// Writes `script` into `dir` and runs it with --quiet (in `dir`); returns the result.
Result run_lua(const McDir& dir, const std::string& script, const std::vector<std::string>& args = {},
               bool quiet = true, double timeout = 60) {
  const std::string path = dir.write("script.lua", script);
  std::vector<std::string> argv;
  if (quiet) argv.push_back("--quiet");
  argv.push_back(path);
  argv.insert(argv.end(), args.begin(), args.end());
  return run_torte(dir, argv, timeout, dir.path.string());
}

// Runs a script that must succeed and print "ok" last; returns stdout.
std::string run_ok(const McDir& dir, const std::string& script, const std::vector<std::string>& args = {}) {
  const Result r = run_lua(dir, script, args);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::EndsWith("ok\n"));
  return r.out;
}

}  // namespace

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

// ---- worlds -----------------------------------------------------------------------------------------------------

namespace {

struct Probe {
  int x, y, z;
  const char* raw;     // as stored: "minecraft:<name>" or "<id>:<data>"
  const char* block;   // the modern name the registry gives the voxel there ("air" when empty)
};

// The biome tint class at a position (from the raw biome id or name there, decoded independently by a Python
// script over scripts/mc_reference.py, then mapped by hand to minecraft.biomes' classes) and the tint the voxel there
// carries ("nil": the block is not tinted).
struct TintProbe {
  int x, y, z;
  const char* cls;
  const char* voxel_tint;
};

// The registry key (and so the cell shape) of the voxel at a position. For 1.13+ worlds the connections are the
// block state's north/east/south/west properties as the Python decoder prints them; pre-1.13 worlds are computed
// from neighbours (the debug world's blocks stand alone: no connection, walls with their post).
struct ShapeProbe {
  int x, y, z;
  const char* key;
};

struct World {
  const char* dir;
  int chunks, full;
  int data_version;  // 0: no DataVersion tag (1.8.9)
  long long non_air;
  const char* format;
  std::vector<Probe> probes;
  std::vector<TintProbe> tints = {};
  std::vector<ShapeProbe> shapes = {};
};

// Counts: SOURCES.md and scripts/mc_reference.py agree on all of them. Probes: scripts/mc_reference.py.
const World kWorldList[] = {
    {"bluenbt-1.20.1-paper", 633, 195, 3465, 8371899, "root/block_states",
     {{256, 80, 16, "minecraft:stone", "minecraft:stone"},
      {34, -60, 93, "minecraft:deepslate", "minecraft:deepslate"},
      {158, -7, 158, "minecraft:sculk_vein", "minecraft:sculk_vein"},
      {256, 81, 16, "minecraft:stone", "minecraft:stone"},
      {35, -61, 93, "minecraft:deepslate", "minecraft:deepslate"}},
     {{8, 62, 136, "ocean", "ocean"},           // water in minecraft:river
      {56, 131, 168, "badlands", "badlands"}},  // grass_block in minecraft:eroded_badlands
     {{0, -46, 14, "minecraft:deepslate_tile_wall,c=0101"},  // west/east low, up false
      {25, 84, 27, "minecraft:dark_oak_fence,c=1000"},
      {19, -47, 32, "minecraft:glass_pane,c=1010"},
      {22, -47, 50, "minecraft:glass_pane,c=0111"},
      {61, 86, 40, "minecraft:dark_oak_fence,c=0100"}}},
    {"mcaselector-anvil112", 103, 103, 1343, 66859, "Level/Blocks",
     {{17, 70, 33, "51:8", "minecraft:fire"}, {17, 71, 33, "0:0", "air"}, {18, 70, 33, "0:0", "air"}},
     {},
     {{79, 70, 25, "minecraft:nether_brick_fence,c=0000"},
      {67, 70, 67, "minecraft:oak_fence,c=0000"},
      {91, 70, 3, "minecraft:cobblestone_wall,c=0000u"},
      {73, 70, 1, "minecraft:glass_pane,c=0000"}}},
    {"mcaselector-anvil113", 147, 147, 1631, 79325, "Level/Palette (spanning)",
     {{17, 70, 161, "minecraft:yellow_bed", "minecraft:yellow_bed"},
      {17, 71, 161, "minecraft:air", "air"},
      {18, 70, 161, "minecraft:air", "air"}},
     {},
     {{91, 70, 1, "minecraft:iron_bars,c=1100"},
      {113, 70, 1, "minecraft:mossy_cobblestone_wall,c=1111"},   // up false
      {113, 70, 17, "minecraft:mossy_cobblestone_wall,c=1101"}}},
    {"prismarine-1.12.2", 105, 105, 1343, 1751731, "Level/Blocks",
     {{272, 48, -64, "1:0", "minecraft:stone"},
      {397, 68, -35, "18:0", "minecraft:oak_leaves"},
      {100, 57, -6, "1:0", "minecraft:stone"},
      {272, 49, -64, "1:0", "minecraft:stone"},
      {398, 67, -35, "18:8", "minecraft:oak_leaves"}},
     {{56, 77, -72, "mountains", "mountains"},  // water, biome 3
      {120, 62, -56, "forest", "forest"},       // grass, biome 4
      {424, 62, -56, "taiga", "taiga"}}}, 
    {"prismarine-1.14.4", 299, 299, 1976, 4746732, "Level/Palette (spanning)",
     {{304, 16, -176, "minecraft:granite", "minecraft:granite"},
      {306, 36, -99, "minecraft:stone", "minecraft:stone"},
      {251, 73, -38, "minecraft:birch_leaves", "minecraft:birch_leaves"},
      {304, 17, -176, "minecraft:stone", "minecraft:stone"},
      {307, 35, -99, "minecraft:stone", "minecraft:stone"}},
     {{72, 62, -200, "ocean", "ocean"},               // water, biome 0
      {424, 62, -152, "dark_forest", "dark_forest"},  // water, biome 29
      {376, 62, -200, "plains", "plains"}},           // water, biome 16 (beach)
     {{357, 15, -198, "minecraft:oak_fence,c=0010"}, {378, 23, -186, "minecraft:oak_fence,c=0001"}}},
    {"prismarine-1.16", 253, 253, 2566, 5082508, "Level/Palette (padded)",
     {{192, 16, -144, "minecraft:stone", "minecraft:stone"},
      {324, 84, -83, "minecraft:water", "minecraft:water"},
      {356, 105, -38, "minecraft:stone", "minecraft:stone"},
      {192, 17, -144, "minecraft:stone", "minecraft:stone"},
      {325, 83, -83, "minecraft:grass_block", "minecraft:grass_block"}},
     {{72, 62, -168, "birch_forest", "birch_forest"},  // grass_block, 3D biome 27
      {328, 76, -168, "mountains", "mountains"},       // grass_block, biome 3
      {104, 71, -136, "forest", "forest"}}},           // oak_leaves, biome 18
    {"prismarine-1.21.1", 225, 16, 3955, 499827, "root/block_states",
     {{48, -48, 0, "minecraft:deepslate", "minecraft:deepslate"},
      {3, -44, 45, "minecraft:deepslate", "minecraft:deepslate"},
      {1, 64, 61, "minecraft:oak_log", "minecraft:oak_log"},
      {48, -47, 0, "minecraft:deepslate_diamond_ore", "minecraft:deepslate_diamond_ore"},
      {4, -45, 45, "minecraft:deepslate", "minecraft:deepslate"}},
     {{8, 62, 8, "plains", "plains"}, {24, 62, 8, "ocean", "ocean"}, {24, 62, 24, "forest", "forest"}}},
    {"prismarine-1.8.9", 300, 300, 0, 4948489, "Level/Blocks",
     {{-48, 48, 112, "1:0", "minecraft:stone"},
      {-190, 4, 253, "1:0", "minecraft:stone"},
      {-92, 41, 362, "1:0", "minecraft:stone"},
      {-48, 49, 112, "1:0", "minecraft:stone"},
      {-189, 3, 253, "7:0", "minecraft:bedrock"}},
     {{-152, 72, 56, "taiga", "nil"},     // spruce leaves (18:1) keep their own colour
      {-120, 63, 56, "taiga", "taiga"},   // grass, biome 5
      {-136, 62, 56, "ocean", "ocean"},   // water, biome 7 (river)
      {-8, 62, 280, "forest", "forest"},  // water, biome 4
      {-152, 62, 328, "plains", "plains"}}},  // water, biome 16 (beach)
    {"querz-nbt-1.18-21w44a-lushcave", 1, 1, 2845, 31961, "root/block_states",
     {{7728, -48, -4208, "minecraft:deepslate", "minecraft:deepslate"},
      {7730, 4, -4195, "minecraft:stone", "minecraft:stone"},
      {7732, 57, -4198, "minecraft:water", "minecraft:water"},
      {7728, -47, -4208, "minecraft:deepslate", "minecraft:deepslate"},
      {7731, 3, -4195, "minecraft:deepslate", "minecraft:deepslate"}},
     {{7732, 57, -4198, "mountains", "mountains"},  // water in minecraft:stony_shore (a 2-entry biome palette)
      {7730, 4, -4195, "plains", "nil"}}},          // stone in minecraft:lush_caves
    {"querz-nbt-1.18.2", 562, 154, 2975, 4923982, "root/block_states",
     {{96, 16, 32, "minecraft:stone", "minecraft:stone"},
      {66, -12, 109, "minecraft:deepslate", "minecraft:deepslate"},
      {20, -7, 170, "minecraft:deepslate", "minecraft:deepslate"},
      {96, 17, 32, "minecraft:air", "air"},
      {67, -13, 109, "minecraft:deepslate", "minecraft:deepslate"}},
     {{56, 62, 8, "frozen_ocean", "frozen_ocean"}, {88, 62, 8, "frozen_ocean", "frozen_ocean"}}},  // deep_frozen
};

// Loads world=<dir> with probes=x,y,z;...; prints "key value" lines.
const char kWorldScript[] = R"LUA(
local world = require "minecraft.world"
local blocks = require "minecraft.blocks"
local args = torte.args
local function positions(s)
  local out = {}
  for x, y, z in tostring(s or ""):gmatch("(%-?%d+),(%-?%d+),(%-?%d+)") do
    out[#out + 1] = {tonumber(x), tonumber(y), tonumber(z)}
  end
  return out
end
local probes = positions(args.probes)
local tints, shapes = positions(args.tints), positions(args.shapes)
local np = #probes
for _, p in ipairs(tints) do probes[#probes + 1] = p end
local sections = {}
local reg = blocks.registry()
local st = world.load{dir = args.world, registry = reg, probes = probes,
                      sink = function(cx, cy, cz, ids) sections[cx .. "," .. cy .. "," .. cz] = ids end}
print("chunks " .. st.chunks)
print("full " .. st.full)
print("not_full " .. st.not_full)
for dv, n in pairs(st.data_versions) do print("dv " .. dv .. " " .. n) end
print("non_air " .. st.non_air)
for f, n in pairs(st.formats) do print("format " .. f) end
for i, p in ipairs(probes) do
  local ids = sections[(p[1] // 16) .. "," .. (p[2] // 16) .. "," .. (p[3] // 16)]
  local v = ids and string.unpack("<i2", ids, 2 * (((p[2] & 15) << 8) | ((p[3] & 15) << 4) | (p[1] & 15)) + 1) or 0
  if i <= np then
    print(("probe %d %s %s"):format(i, tostring(st.probes[i]), v == 0 and "air" or reg:name(v)))
  else
    print(("tint %d %s %s"):format(i - np, tostring(st.probe_biomes[i]), tostring(reg:tint(v))))
  end
end
for i, p in ipairs(shapes) do
  local v = world.id_at(sections, p[1], p[2], p[3])
  print(("shape %d %s"):format(i, v == 0 and "air" or reg.entries[v].key))
end
print("ok")
)LUA";

void check_world(const World& w) {
  if (!have_worlds()) return;
  McDir dir(std::string("world_") + w.dir);
  auto pos = [](int x, int y, int z) {
    return std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z) + ";";
  };
  std::string probes, tints, shapes;
  for (const Probe& p : w.probes) probes += pos(p.x, p.y, p.z);
  for (const TintProbe& p : w.tints) tints += pos(p.x, p.y, p.z);
  for (const ShapeProbe& p : w.shapes) shapes += pos(p.x, p.y, p.z);
  const std::string out = run_ok(dir, kWorldScript, {"world=" + (kWorlds / w.dir).string(), "probes=" + probes,
                                                     "tints=" + tints, "shapes=" + shapes});
  const std::vector<std::string> lines = lines_of(out);
  auto has = [&](const std::string& line) {
    INFO("expected line: " << line << "\nstdout:\n" << out);
    CHECK(std::find(lines.begin(), lines.end(), line) != lines.end());
  };
  has("chunks " + std::to_string(w.chunks));
  has("full " + std::to_string(w.full));
  has("not_full " + std::to_string(w.chunks - w.full));
  has("dv " + std::to_string(w.data_version) + " " + std::to_string(w.chunks));  // one DataVersion per world
  has("non_air " + std::to_string(w.non_air));
  has(std::string("format ") + w.format);
  for (size_t i = 0; i < w.probes.size(); ++i)
    has("probe " + std::to_string(i + 1) + " " + w.probes[i].raw + " " + w.probes[i].block);
  for (size_t i = 0; i < w.tints.size(); ++i)
    has("tint " + std::to_string(i + 1) + " " + w.tints[i].cls + " " + w.tints[i].voxel_tint);
  for (size_t i = 0; i < w.shapes.size(); ++i) has("shape " + std::to_string(i + 1) + " " + w.shapes[i].key);
}

}  // namespace

TEST_CASE("minecraft world: 1.20.1 paper world (root block_states, minecraft:full status)", "[minecraft]") {
  check_world(kWorldList[0]);
}
TEST_CASE("minecraft world: 1.12.2 debug world (numeric ids, data nibbles)", "[minecraft]") {
  check_world(kWorldList[1]);
}
TEST_CASE("minecraft world: 1.13.2 debug world (palettes spanning longs, postprocessed status)", "[minecraft]") {
  check_world(kWorldList[2]);
}
TEST_CASE("minecraft world: 1.12.2 terrain (numeric ids)", "[minecraft]") { check_world(kWorldList[3]); }
TEST_CASE("minecraft world: 1.14.4 terrain (palettes spanning longs, light-only sections)", "[minecraft]") {
  check_world(kWorldList[4]);
}
TEST_CASE("minecraft world: 1.16 terrain (padded palettes)", "[minecraft]") { check_world(kWorldList[5]); }
TEST_CASE("minecraft world: 1.21.1 terrain (mostly unfinished chunks)", "[minecraft]") {
  check_world(kWorldList[6]);
}
TEST_CASE("minecraft world: 1.8.9 terrain (no DataVersion)", "[minecraft]") { check_world(kWorldList[7]); }
TEST_CASE("minecraft world: 1.18 snapshot lush cave (one chunk, y from -64)", "[minecraft]") {
  check_world(kWorldList[8]);
}
TEST_CASE("minecraft world: 1.18.2 terrain (partly generated chunks skipped)", "[minecraft]") {
  check_world(kWorldList[9]);
}

TEST_CASE("minecraft world: level.dat is gzip NBT naming the version", "[minecraft]") {
  if (!have_worlds()) return;
  McDir dir("level_dat");
  run_ok(dir, R"LUA(
local raw = torte.data.gunzip(torte.data.read_file(torte.args.file))
local root = torte.data.nbt(raw)
assert(root.Data.Version.Name == "1.20.1" and root.Data.Version.Id == 3465, root.Data.Version.Name)
assert(root.Data.DataVersion == 3465)
print("ok")
)LUA",
         {"file=" + (kWorlds / "bluenbt-1.20.1-paper" / "level.dat").string()});
}

namespace {

// Copies a region file into `dir`, applies `edit` to its bytes and writes it under the same name.
std::string damaged_copy(const McDir& dir, const std::string& name, const std::string& world, const std::string& file,
                         void (*edit)(std::string&)) {
  std::string bytes = read_file((kWorlds / world / file).string());
  edit(bytes);
  fs::create_directories(dir.path / name);
  std::ofstream(dir / (name + "/" + file), std::ios::binary) << bytes;
  return dir / name;
}

// Byte offset of the first chunk in the file's location table.
size_t first_chunk(const std::string& bytes) {
  for (size_t i = 0; i < 1024; ++i) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 4 * i;
    const size_t sector = (size_t(p[0]) << 16) | (size_t(p[1]) << 8) | p[2];
    if (sector) return sector * 4096;
  }
  return 0;
}

// Loads each world=<dir> (comma-separated) strictly, then with skip_bad_chunks; prints what happened.
const char kLoadScript[] = R"LUA(
local world = require "minecraft.world"
for dir in tostring(torte.args.worlds):gmatch("[^,]+") do
  local ok, err = pcall(world.load, {dir = dir, progress = false})
  print("strict " .. (ok and "loaded" or err))
  local st = world.load{dir = dir, skip_bad_chunks = true, progress = not torte.quiet}
  print(("skipping full %d bad %d first %s"):format(st.full, st.bad, tostring(st.bad_messages[1])))
end
print("ok")
)LUA";

}  // namespace

TEST_CASE("minecraft world: damaged regions are errors naming file and chunk, or skipped on request",
          "[minecraft]") {
  if (!have_worlds()) return;
  McDir dir("damaged");
  struct Case {
    const char* name;
    void (*edit)(std::string&);
    const char* message;
  };
  const Case cases[] = {
      {"zlib", [](std::string& b) { for (size_t i = 10; i < 40; ++i) b[first_chunk(b) + 5 + i] ^= 0x5a; },
       "torte.data.inflate: corrupt input"},
      {"nbt", [](std::string& b) { b[first_chunk(b) + 4] = 3; },  // zlib bytes read as uncompressed NBT
       "torte.data.nbt: unknown root tag type 120"},
      {"short",
       [](std::string& b) {  // the chunk's length cut to 40 bytes: a zlib stream that ends early
         const size_t at = first_chunk(b);
         b[at] = b[at + 1] = b[at + 2] = 0;
         b[at + 3] = 40;
       },
       "torte.data.inflate: truncated input"},
      {"cut", [](std::string& b) { b.resize(300000); }, "truncated region file"},
  };
  std::string worlds;
  for (const Case& c : cases) {
    const std::string w = damaged_copy(dir, c.name, "prismarine-1.12.2", "r.0.-1.mca", c.edit);
    worlds += (worlds.empty() ? "" : ",") + w;
  }
  // All cases in one process (each start costs ~0.5 s); the error strings are what the top level would print.
  const std::string out = run_ok(dir, kLoadScript, {"worlds=" + worlds});
  const std::vector<std::string> lines = lines_of(out);
  REQUIRE(lines.size() == 2 * std::size(cases) + 1);
  for (size_t i = 0; i < std::size(cases); ++i) {
    INFO("case " << cases[i].name << ": " << lines[2 * i] << "\n" << lines[2 * i + 1]);
    CHECK_THAT(lines[2 * i], Catch::StartsWith("strict " + (dir.path / cases[i].name).string()));
    CHECK_THAT(lines[2 * i], Catch::Contains("/r.0.-1.mca: chunk ("));
    CHECK_THAT(lines[2 * i], Catch::Contains(cases[i].message));
    CHECK_THAT(lines[2 * i + 1], Catch::Contains(cases[i].message));
    if (i < 3) CHECK_THAT(lines[2 * i + 1], Catch::StartsWith("skipping full 104 bad 1 "));
  }
  // The cut file: some chunks lost, the rest loaded.
  int full = 0, bad = 0;
  REQUIRE(std::sscanf(lines[7].c_str(), "skipping full %d bad %d", &full, &bad) == 2);
  CHECK(full > 0);
  CHECK(bad > 0);
  CHECK(full + bad == 105);

  {  // as a script error, and the progress and skip notes without --quiet
    const std::string cut = (dir.path / "cut").string();
    const std::string line = check_error(run_lua(dir, R"LUA(
require("minecraft.world").load{dir = torte.args.world})LUA", {"world=" + cut}));
    CHECK_THAT(line, Catch::Contains("/r.0.-1.mca: chunk ("));
    CHECK_THAT(line, Catch::Contains("truncated region file"));
    const Result s = run_lua(dir, kLoadScript, {"worlds=" + cut}, /*quiet=*/false);
    INFO("stderr: " << s.err);
    CHECK(s.code == 0);
    CHECK_THAT(s.err, Catch::Contains("100% of 105 chunks"));
    CHECK_THAT(s.err, Catch::Contains("minecraft: skipped " + std::to_string(bad) + " bad chunks"));
  }
}

TEST_CASE("minecraft blocks: definitions, legacy ids, fallback and every look builds", "[minecraft]") {
  McDir dir("blocks");
  run_ok(dir, R"LUA(
local blocks = require "minecraft.blocks"
local reg = blocks.registry()
local function legacy(id, data) return reg:name(reg:legacy(id, data)) end
assert(legacy(1, 0) == "minecraft:stone" and legacy(1, 1) == "minecraft:granite")
assert(legacy(2, 0) == "minecraft:grass_block" and legacy(3, 2) == "minecraft:podzol")
assert(legacy(17, 2) == "minecraft:birch_log" and legacy(18, 8) == "minecraft:oak_leaves")
assert(legacy(162, 1) == "minecraft:dark_oak_log" and legacy(35, 14) == "minecraft:red_wool")
assert(legacy(159, 1) == "minecraft:orange_terracotta" and legacy(98, 1) == "minecraft:mossy_stone_bricks")
assert(reg:legacy(17, 4) ~= reg:legacy(17, 0) and legacy(17, 4) == "minecraft:oak_log", "a log along x")
assert(reg:state("minecraft:oak_log", {axis = "y"}) == reg:legacy(17, 0))
assert(legacy(0, 0) == nil and reg:legacy(0, 0) == 0, "air is 0")
-- Slabs and stairs are cell shapes (< 0), with top/bottom and facing as separate ids.
local bottom, top = reg:legacy(44, 0), reg:legacy(44, 8)
assert(bottom < 0 and top < 0 and bottom ~= top)
assert(reg:state("minecraft:stone_slab", {type = "double"}) < 0)
assert(reg:state("minecraft:oak_stairs", {facing = "north", half = "bottom"})
       ~= reg:state("minecraft:oak_stairs", {facing = "south", half = "bottom"}))
assert(reg:state("minecraft:stone") > 0 and reg:state("minecraft:stone") == reg:state("minecraft:stone", {}))
assert(reg:state("minecraft:poppy") < 0 and reg:state("minecraft:torch") < 0)
assert(reg:state("minecraft:barrier") == 0 and reg:state("minecraft:cave_air") == 0)
-- Unknown blocks: a visible fallback id, counted by the loader, not an error.
local u = reg:state("minecraft:no_such_block")
assert(u > 0 and reg:name(u) == "minecraft:no_such_block")
reg:count_unknown(u, 7)
reg:count_unknown(reg:state("minecraft:stone"), 5)
assert(reg.unknown["minecraft:no_such_block"] == 7 and reg.unknown_blocks == 7)
-- Emitters.
assert(reg:emission(reg:state("minecraft:glowstone")) and reg:emission(reg:state("minecraft:lava")))
assert(reg:emission(reg:state("minecraft:torch")) and not reg:emission(reg:state("minecraft:dirt")))
-- The common blocks are all known (not the fallback).
local common = [[stone granite diorite andesite deepslate cobblestone mossy_cobblestone bedrock dirt coarse_dirt
  podzol grass_block sand red_sand gravel clay sandstone red_sandstone coal_ore iron_ore gold_ore diamond_ore
  redstone_ore lapis_ore emerald_ore copper_ore deepslate_iron_ore oak_log spruce_log birch_log jungle_log acacia_log
  dark_oak_log oak_leaves spruce_leaves birch_leaves jungle_leaves acacia_leaves dark_oak_leaves oak_planks
  spruce_planks birch_planks glass white_stained_glass water lava torch wall_torch glowstone sea_lantern snow
  snow_block ice packed_ice grass short_grass tall_grass fern dandelion poppy blue_orchid oxeye_daisy dead_bush
  sugar_cane cactus pumpkin melon oak_slab stone_slab cobblestone_stairs oak_stairs stone_brick_stairs stone_bricks
  bricks obsidian bookshelf crafting_table furnace chest oak_fence cobblestone_wall terracotta white_terracotta
  orange_terracotta white_wool red_wool white_concrete farmland dirt_path mycelium netherrack soul_sand
  magma_block iron_block gold_block diamond_block coal_block hay_block rail vine lily_pad brown_mushroom
  red_mushroom moss_block tuff calcite smooth_stone oak_door glass_pane]]
local n = 0
for name in common:gmatch("%S+") do
  n = n + 1
  assert(blocks.definition(name), "no definition for " .. name)
end
assert(n >= 100, n)
-- Every definition builds: define one id per known name into a grid (materials, textures, cell shapes).
local all = blocks.registry()
for name in pairs(blocks.DEFS) do
  all:state("minecraft:" .. name, {type = "top", facing = "east", half = "top", layers = "3"})
  all:state("minecraft:" .. name, {axis = "x"})
end
all:state("minecraft:no_such_block")
local grid = torte.voxel.grid{}
all:define(grid)
print("ok")
)LUA");
}

TEST_CASE("minecraft scene: a missing world renders the empty sky, with a notice unless quiet", "[minecraft]") {
  McDir dir("scene_missing");
  const std::string scene = (fs::path(TORTE_SOURCE_DIR) / "scenes" / "minecraft.lua").string();
  const std::vector<std::string> args = {scene, "world=" + (dir / "no-world"), "width=16", "height=16", "spp=1",
                                         "output=" + (dir / "sky.exr")};
  std::vector<std::string> quiet = {"--quiet"};
  quiet.insert(quiet.end(), args.begin(), args.end());
  const Result q = run_torte(dir, quiet, 60);
  INFO("stderr: " << q.err);
  CHECK(q.code == 0);
  CHECK(q.err.empty());
  CHECK(fs::exists(dir / "sky.exr"));
  const Result loud = run_torte(dir, args, 60);
  CHECK(loud.code == 0);
  CHECK_THAT(loud.err, Catch::Contains("minecraft.lua: world '"));
  CHECK_THAT(loud.err, Catch::Contains("not found"));
}

TEST_CASE("minecraft scene: the lush cave world by bare name, with a box and a camera", "[minecraft]") {
  if (!have_worlds()) return;
  McDir dir("scene_cave");
  const std::string scene = (fs::path(TORTE_SOURCE_DIR) / "scenes" / "minecraft.lua").string();
  const Result r = run_torte(dir,
                             {"--quiet", scene, "world=querz-nbt-1.18-21w44a-lushcave", "width=24", "height=16",
                              "spp=1", "box=7728,-64,-4208,7744,64,-4192", "camera=7700,40,-4230,7736,0,-4200",
                              "output=" + (dir / "cave.exr")},
                             60);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK(fs::exists(dir / "cave.png"));
  const std::string bad = check_error(run_torte(dir, {"--quiet", scene, "box=1,2,3", "output=" + (dir / "x.exr")}, 60));
  CHECK_THAT(bad, Catch::Contains("'box' needs 6"));
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

namespace {

// Lua helpers for the tests below: an NBT writer, an Anvil region writer and a 1.12-format chunk.
const char kRegionWriter[] = R"LUA(
local P = string.pack
local W = {}
local function tag(t, n, payload) return P("B", t) .. P(">s2", n) .. payload end
W.tag = tag
function W.compound(fields) return table.concat(fields) .. "\0" end
-- A region file at `path` holding `chunks` ({lx, lz, payload bytes}) with compression byte `compression`.
function W.region(path, chunks, compression)
  local loc, body, sector = {}, {}, 2
  for _, c in ipairs(chunks) do
    local bytes = P(">I4B", #c[3] + 1, compression) .. c[3]
    local n = (#bytes + 4095) // 4096
    body[#body + 1] = bytes .. ("\0"):rep(n * 4096 - #bytes)
    loc[c[1] + 32 * c[2]] = (sector << 8) | n
    sector = sector + n
  end
  local h = {}
  for i = 0, 1023 do h[#h + 1] = P(">I4", loc[i] or 0) end
  for i = 0, 1023 do h[#h + 1] = P(">I4", 1700000000) end
  local f = assert(io.open(path, "wb"))
  f:write(table.concat(h), table.concat(body))
  f:close()
end
-- One pre-1.13 chunk (DataVersion 1343) at (cx, cz) with one section Y=4 (y 64..79): blocks {[{x, y, z}] = id}
-- in chunk-local coordinates (y 0..15 in the section) and a biome id per column from biome(x, z).
function W.legacy_chunk(cx, cz, blocks, biome)
  local b = {}
  for i = 1, 4096 do b[i] = 0 end
  for _, e in ipairs(blocks) do b[((e[2] * 16 + e[3]) * 16 + e[1]) + 1] = e[4] end
  local bytes = {}
  for i = 1, 4096 do bytes[i] = string.char(b[i]) end
  local cols = {}
  for z = 0, 15 do for x = 0, 15 do cols[#cols + 1] = string.char(biome(x, z)) end end
  local section = W.compound{tag(1, "Y", P(">i1", 4)), tag(7, "Blocks", P(">i4", 4096) .. table.concat(bytes)),
                             tag(7, "Data", P(">i4", 2048) .. ("\0"):rep(2048))}
  local level = tag(10, "Level", W.compound{tag(3, "xPos", P(">i4", cx)), tag(3, "zPos", P(">i4", cz)),
                                            tag(9, "Sections", P(">Bi4", 10, 1) .. section),
                                            tag(7, "Biomes", P(">i4", 256) .. table.concat(cols))})
  return tag(10, "", W.compound{level, tag(3, "DataVersion", P(">i4", 1343))})
end
return W
)LUA";

// `script` run with the writer above available as the local W (writer.lua in `dir`, found through package.path).
std::string run_ok_with_writer(const McDir& dir, const std::string& script,
                               const std::vector<std::string>& args = {}) {
  dir.write("writer.lua", kRegionWriter);
  return run_ok(dir, "package.path = \"./?.lua;\" .. package.path\nlocal W = require \"writer\"\n" + script, args);
}

}  // namespace

TEST_CASE("minecraft region: LZ4 chunks (LZ4Block streams) load like zlib ones; bad streams name file and chunk",
          "[minecraft]") {
  if (!have_worlds()) return;
  McDir dir("lz4_region");
  fs::create_directories(dir.path / "lz4");
  fs::create_directories(dir.path / "bad");
  const std::string out = run_ok_with_writer(dir, R"LUA(
local region = require "minecraft.region"
local world = require "minecraft.world"
local D = torte.data
-- The stream format itself: several blocks (16 KiB each), a raw (incompressible) block, the end block.
local parts = {}
local x = 12345
for i = 1, 20000 do
  x = (x * 1103515245 + 12345) & 0x7fffffff
  parts[i] = string.char((x >> 16) & 255)
end
local noise = table.concat(parts)
for _, s in ipairs({("abc"):rep(30000), noise, "", "z"}) do
  local enc = region.lz4_stream_encode(s, 16384)
  assert(region.lz4_stream(enc) == s)
end
assert(region.lz4_stream_encode(noise, 65536):byte(9) == 0x16, "incompressible data is stored raw (0x10 | level 6)")
-- Re-encode every chunk of a real region as LZ4 (compression byte 4), in blocks of 8 KiB.
local src = torte.args.world .. "/r.0.-1.mca"
local r = region.open(src)
local chunks = {}
for _, c in ipairs(r:chunks()) do
  chunks[#chunks + 1] = {c.lx, c.lz, region.lz4_stream_encode(r:payload(c), 8192)}
end
W.region("lz4/r.0.-1.mca", chunks, 4)
local function load(dir)
  local sections = {}
  local st = world.load{dir = dir, sink = function(cx, cy, cz, ids) sections[cx .. "," .. cy .. "," .. cz] = ids end}
  return st, sections
end
local a, sa = load(torte.args.world)
local b, sb = load("lz4")
assert(a.chunks == b.chunks and a.full == b.full and a.non_air == b.non_air and a.sections == b.sections)
local n = 0
for k, ids in pairs(sa) do
  assert(sb[k] == ids, k)
  n = n + 1
end
print("sections " .. n)
-- Damaged streams, one chunk each: the loader's error names the file and the chunk.
local good = region.lz4_stream_encode(r:payload(r:chunks()[1]), 8192)
local cases = {
  magic = "LZ5Block" .. good:sub(9),
  truncated = good:sub(1, 300),
  no_end = good:sub(1, -22),
  size = good:sub(1, 13) .. string.pack("<i4", string.unpack("<i4", good, 14) - 1) .. good:sub(18),
  checksum = good:sub(1, 17) .. string.pack("<I4", (string.unpack("<I4", good, 18) + 1) & 0x0FFFFFFF) .. good:sub(22),
  data = good:sub(1, 40) .. "\255\255\255\255" .. good:sub(45),
  method = good:sub(1, 8) .. "\x36" .. good:sub(10),
  trailing = good .. "xyz",
}
local short = region.lz4_stream_encode(("abc"):rep(100))
cases.size_big = short:sub(1, 13) .. string.pack("<i4", 301) .. short:sub(18)
for _, name in ipairs({"magic", "truncated", "no_end", "size", "size_big", "checksum", "data", "method", "trailing"}) do
  local bytes = cases[name]
  W.region("bad/r.0.-1.mca", {{1, 31, bytes}}, 4)
  local ok, e = pcall(world.load, {dir = "bad"})
  assert(not ok)
  assert(e:find("bad/r.0.-1.mca: chunk (1, -1) (entry 1,31 of the region): LZ4 block ", 1, true), e)
  print(name .. ": " .. e:match("LZ4 block .*"))
end
print("ok")
)LUA",
                                 {"world=" + (kWorlds / "prismarine-1.12.2").string()});
  const std::vector<std::string> lines = lines_of(out);
  auto has = [&](const std::string& line) {
    INFO("expected line: " << line << "\nstdout:\n" << out);
    CHECK(std::find(lines.begin(), lines.end(), line) != lines.end());
  };
  has("sections 534");
  has("magic: LZ4 block 1 at byte 0: bad magic (expected 'LZ4Block')");
  has("truncated: LZ4 block 1 at byte 0: truncated input: 1045 compressed bytes, 279 left");
  has("no_end: LZ4 block 9 at byte 5214: truncated input: the stream ends without its end block");
  has("method: LZ4 block 1 at byte 0: unknown compression method 0x30");
  has("trailing: LZ4 block 9 at byte 5214: 3 bytes of trailing data after the end block");
  has("size_big: LZ4 block 1 at byte 0: torte.data.lz4_block: size mismatch: the block decompresses to 300 bytes, "
      "expected 301");
  has("checksum: LZ4 block 1 at byte 0: checksum mismatch (corrupt data)");
  CHECK_THAT(out, Catch::Contains("size: LZ4 block 1 at byte 0: torte.data.lz4_block: corrupt or truncated input"));
  CHECK_THAT(out, Catch::Contains("data: LZ4 block 1 at byte 0: "));
}

TEST_CASE("minecraft world: pre-1.13 fences, walls, panes join their neighbours; biomes tint per column",
          "[minecraft]") {
  McDir dir("connect");
  fs::create_directories(dir.path / "w");
  const std::string out = run_ok_with_writer(dir, R"LUA(
local world = require "minecraft.world"
local blocks = require "minecraft.blocks"
-- Ids: 1 stone, 2 grass, 9 water, 20 glass, 85 oak fence, 101 iron bars, 102 glass pane, 107 fence gate,
-- 113 nether brick fence, 139 cobblestone wall, 160 stained glass pane. Section y 0 = world y 64.
local a = {
  {13, 0, 2, 85}, {14, 0, 2, 85}, {15, 0, 2, 85},        -- a fence row running into the next chunk
  {5, 0, 4, 1}, {5, 0, 5, 85}, {6, 0, 5, 20}, {4, 0, 5, 113}, {5, 0, 6, 107},  -- stone N, glass E, nether W, gate S
  {8, 0, 7, 20}, {8, 0, 8, 102}, {9, 0, 8, 101}, {8, 0, 9, 1},   -- a pane between glass, bars and stone
  {8, 0, 12, 160}, {9, 0, 12, 102},                     -- stained and plain panes join
  {2, 0, 10, 139}, {2, 0, 11, 139}, {2, 0, 12, 139},    -- a straight wall, air above: no post in the middle
  {11, 0, 10, 139}, {11, 0, 11, 139}, {11, 0, 12, 139}, {11, 1, 11, 1},  -- the same with a block above
  {1, 0, 14, 2}, {12, 0, 14, 2}, {3, 1, 3, 9},          -- grass in forest and swamp columns, water
}
local b = {{0, 0, 2, 85}}
-- Biomes: forest (4) for x < 8, swamp (6) for x >= 8 in chunk (0, 0); chunk (1, 0) all plains (1).
W.region("w/r.0.0.mca", {{0, 0, W.legacy_chunk(0, 0, a, function(x) return x < 8 and 4 or 6 end)},
                         {1, 0, W.legacy_chunk(1, 0, b, function() return 1 end)}}, 3)
local reg = blocks.registry()
local sections = {}
local st = world.load{dir = "w", registry = reg, sink = function(cx, cy, cz, ids) sections[cx .. "," .. cy .. "," .. cz] = ids end}
assert(st.full == 2 and st.connected_sections == 2, st.connected_sections)
for _, p in ipairs({{13, 2}, {14, 2}, {15, 2}, {16, 2}, {5, 5}, {4, 5}, {8, 8}, {9, 8}, {8, 12}, {9, 12}, {2, 10},
                    {2, 11}, {2, 12}, {11, 11}, {1, 14}, {12, 14}}) do
  local v = world.id_at(sections, p[1], 64, p[2])
  print(("%d,%d %s %s"):format(p[1], p[2], reg.entries[v].key, tostring(reg:tint(v))))
end
local v = world.id_at(sections, 3, 65, 3)
print("water " .. reg.entries[v].key)
-- Every shape builds.
reg:define(torte.voxel.grid{})
print("ok")
)LUA");
  const std::vector<std::string> lines = lines_of(out);
  auto has = [&](const std::string& line) {
    INFO("expected line: " << line << "\nstdout:\n" << out);
    CHECK(std::find(lines.begin(), lines.end(), line) != lines.end());
  };
  // Connection codes: north, east, south, west (0 none, 1 joined, 2 tall), then "u" when a wall shows its post.
  has("13,2 minecraft:oak_fence,c=0100 nil");
  has("14,2 minecraft:oak_fence,c=0101 nil");
  has("15,2 minecraft:oak_fence,c=0101 nil");  // joined across the chunk border
  has("16,2 minecraft:oak_fence,c=0001 nil");
  has("5,5 minecraft:oak_fence,c=1010 nil");   // stone and gate; not glass, not the nether brick fence
  has("4,5 minecraft:nether_brick_fence,c=0000 nil");
  has("8,8 minecraft:glass_pane,c=1110 nil");  // glass, bars and stone
  has("9,8 minecraft:iron_bars,c=0001 nil");
  has("8,12 minecraft:white_stained_glass_pane,c=0100 nil");
  has("9,12 minecraft:glass_pane,c=0001 nil");
  has("2,10 minecraft:cobblestone_wall,c=0010u nil");
  has("2,11 minecraft:cobblestone_wall,c=1010 nil");
  has("2,12 minecraft:cobblestone_wall,c=1000u nil");
  has("11,11 minecraft:cobblestone_wall,c=1010u nil");
  has("1,14 minecraft:grass_block@forest forest");
  has("12,14 minecraft:grass_block@swamp swamp");
  has("water minecraft:water@forest");
}

TEST_CASE("minecraft blocks: connection states, biome variants and their looks", "[minecraft]") {
  McDir dir("variants");
  run_ok(dir, R"LUA(
local blocks = require "minecraft.blocks"
local biomes = require "minecraft.biomes"
local reg = blocks.registry()
-- 1.13+ states: the connection properties pick the shape; "true" (walls before 1.16) and "low" are the same.
local function fence(n, e, s, w)
  return reg:state("minecraft:oak_fence", {north = n, east = e, south = s, west = w, waterlogged = "false"})
end
local f1, f2 = fence("true", "false", "true", "false"), fence("false", "true", "false", "true")
assert(f1 < 0 and f2 < 0 and f1 ~= f2 and fence("true", "false", "true", "false") == f1)
local w1 = reg:state("minecraft:cobblestone_wall", {north = "true", south = "true", east = "false", west = "false", up = "false"})
local w2 = reg:state("minecraft:cobblestone_wall", {north = "low", south = "low", east = "none", west = "none", up = "false"})
local w3 = reg:state("minecraft:cobblestone_wall", {north = "tall", south = "tall", east = "none", west = "none", up = "false"})
assert(w1 == w2 and w2 ~= w3)
assert(reg.entries[w3].key == "minecraft:cobblestone_wall,c=2020")
assert(reg.family[f1] == "wood_fence" and reg.family[w1] == "wall")
assert(reg.family[reg:state("minecraft:nether_brick_fence")] == "nether_fence")
assert(reg.family[reg:state("minecraft:iron_bars")] == "pane" and reg.family[reg:state("minecraft:red_stained_glass_pane")] == "pane")
assert(reg.family[reg:state("minecraft:oak_fence_gate", {facing = "north"})] == "gate")
assert(reg:solid(reg:state("minecraft:stone")) and not reg:solid(reg:state("minecraft:glass")))
assert(not reg:solid(reg:state("minecraft:oak_leaves")) and not reg:solid(f1))
local c = blocks.connections({north = "true", east = "false", south = "true", west = "false"})
assert(c.north == "low" and not c.east and c.south and not c.west)
-- Biome classes: names and numeric ids.
assert(biomes.class_of("minecraft:dark_forest") == "dark_forest" and biomes.class_of(29) == "dark_forest")
assert(biomes.class_of("minecraft:mangrove_swamp") == "mangrove_swamp" and biomes.class_of(6) == "swamp")
assert(biomes.class_of("minecraft:warm_ocean") == "warm_ocean" and biomes.class_of(44) == "warm_ocean")
assert(biomes.class_of("minecraft:snowy_plains") == "snowy" and biomes.class_of(12) == "snowy")
assert(biomes.class_of("minecraft:badlands") == "badlands" and biomes.class_of(2) == "dry")
assert(biomes.class_of("minecraft:no_such_biome") == "plains" and biomes.class_of(255) == "plains")
assert(#biomes.CLASSES >= 15)
-- Tinted variants: one id per (block state, class), the same sign as the block's id; untinted blocks stay.
local grass, water, leaves = reg:state("minecraft:grass_block"), reg:state("minecraft:water"), reg:state("minecraft:oak_leaves")
local sw = reg:tinted(grass, "swamp")
assert(sw > 0 and sw ~= grass and reg:tinted(grass, "swamp") == sw and reg:tint(sw) == "swamp")
assert(reg:name(sw) == "minecraft:grass_block" and reg:tint(grass) == nil)
assert(reg:tinted(water, "warm_ocean") < 0 and reg:tinted(leaves, "jungle") > 0)
assert(reg.tint_kind[reg:state("minecraft:spruce_leaves")] == nil, "spruce leaves keep their colour")
assert(reg:tinted(reg:state("minecraft:stone"), "swamp") == reg:state("minecraft:stone"))
local set = reg:ids_of("water")
assert(set[water] and set[reg:tinted(water, "warm_ocean")])
-- The tint scales the plains look: darker grass in a dark forest, plains unchanged.
local top = blocks.definition("grass_block").top
local dark = blocks.tint_color(top, "grass", "dark_forest")
assert(dark[2] < top[2] and blocks.tint_color(top, "grass", "plains")[2] == top[2])
-- Every class of every tinted kind and every connection shape builds.
for _, cl in ipairs(biomes.CLASSES) do
  for _, id in ipairs({grass, water, leaves, reg:state("minecraft:vine"), reg:state("minecraft:tall_grass")}) do
    reg:tinted(id, cl)
  end
end
for code = 0, 80 do
  local v = {}
  for k = 1, 4 do v[k] = ({"none", "low", "tall"})[(code // 3 ^ (k - 1)) % 3 + 1] end
  reg:state("minecraft:stone_brick_wall", {north = v[1], east = v[2], south = v[3], west = v[4], up = code % 2 == 0 and "true" or "false"})
  reg:state("minecraft:glass_pane", {north = tostring(v[1] ~= "none"), east = tostring(v[2] ~= "none"),
                                     south = tostring(v[3] ~= "none"), west = tostring(v[4] ~= "none")})
end
reg:define(torte.voxel.grid{})
print("ok")
)LUA");
}

TEST_CASE("minecraft blocks: glowstone torches and fire light a dark scene as voxel area lights", "[minecraft]") {
  McDir dir("emitters");
  // A stone floor under a black sky with three emitting blocks: a cube (glowstone), a torch (an emitting flame box
  // on a stick) and fire (two emitting crossed quads). Without emission the image is black; with it the floor
  // around each emitter is lit and the lit floor shows the emitters' colours.
  const std::string out = run_ok(dir, R"LUA(
local blocks = require "minecraft.blocks"
local function render(emission)
  local reg = blocks.registry()
  local grid = torte.voxel.grid{}
  local stone = reg:state("minecraft:stone")
  for x = -8, 8 do for z = -8, 8 do grid:set(x, 0, z, stone) end end
  grid:set(-4, 1, 0, reg:state("minecraft:glowstone"))
  grid:set(0, 1, 0, reg:state("minecraft:torch"))
  grid:set(4, 1, 0, reg:state("minecraft:fire"))
  reg:define(grid, {emission = emission})
  local scene = torte.scene()
  scene:add(grid:shape{})
  local camera = torte.camera.perspective{eye = {0, 9, -9}, look_at = {0, 0, 0}, up = {0, 1, 0}, fov = 60}
  return torte.render{scene = scene, camera = camera, width = 48, height = 48, spp = 16, max_depth = 3}
end
local lit, dark = render(true), render(false)
local r, g, b = lit:mean()
local r0, g0, b0 = dark:mean()
assert(r0 == 0 and g0 == 0 and b0 == 0, "no emission: black")
assert(r > 0.02 and g > 0.01, ("lit mean %g %g %g"):format(r, g, b))
assert(r > b, "warm light")
-- The floor just in front of each emitter (the camera looks along +z, so world +x is the image's left) is far
-- brighter than the floor in the near corners.
local function window(img, cx, cy)
  local s = 0
  for y = cy - 1, cy + 1 do for x = cx - 2, cx + 2 do local pr, pg, pb = img:pixel(x, y); s = s + pr + pg + pb end end
  return s / 45
end
local corner = (window(lit, 3, 44) + window(lit, 44, 44)) / 2
for _, e in ipairs({{"glowstone", 36, 22, 50}, {"torch", 24, 22, 5}, {"fire", 12, 22, 5}}) do
  local v = window(lit, e[2], e[3])
  assert(v > e[4] * corner and v > 0.002, ("%s: floor %g, corner %g"):format(e[1], v, corner))
end
print("ok")
)LUA");
  (void)out;
}
