// The Minecraft loader in lua/minecraft/ on real worlds and on damaged or hand-made region files, end to end
// through the built binary (TORTE_BINARY).
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

#include "minecraft_support.h"

namespace fs = std::filesystem;
using namespace torte::test;
using namespace torte::test::minecraft;

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
