// Minecraft blocks (lua/minecraft/blocks.lua): definitions, looks, connection states, biome tints and emitters, and
// the minecraft scene script, end to end through the built binary (TORTE_BINARY).
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
-- leaves2 (161) has two woods; data 2 and 3 (corrupt files) fall back to the first instead of a nil concat
assert(legacy(161, 1) == "minecraft:dark_oak_leaves" and legacy(161, 2) == "minecraft:acacia_leaves")
assert(legacy(161, 11) == "minecraft:acacia_leaves")
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
  const Result r = run_lua(dir, R"LUA(
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
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::EndsWith("ok\n"));
  // The dark render is black by design, and says so in one warning line.
  CHECK_THAT(r.err, Catch::StartsWith("torte: warning: ") && Catch::Contains("no lights and no emitting shapes"));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}
