-- minecraft.biomes: biome tint classes and the chunk biome data of every storage format.
--
--   local biomes = require "minecraft.biomes"
--   biomes.class_of("minecraft:dark_forest")  --> "dark_forest"      (1.18+ names, and the older names too)
--   biomes.class_of(6)                        --> "swamp"            (numeric ids, before 1.18)
--   biomes.TINTS.swamp                        --> {grass = {r,g,b}, foliage = {...}, water = {...}} (sRGB 0..1)
--   local b = biomes.section(level, section, cy, dv)   -- the tint classes of one 16^3 section (see below)
--
-- A section's biomes come back as nil (no biome data: blocks keep their untinted look), {uniform = class}, or
-- {cells = {64 classes}} (4x4x4 cells, index (y>>2)*16 + (z>>2)*4 + (x>>2) + 1) or {columns = {256 classes}}
-- (index z*16 + x + 1). Formats:
--   <= 1.12:     Level.Biomes, 256 bytes, one numeric id per column (index z*16 + x; 255 = not generated)
--   1.13-1.14:   Level.Biomes, 256 ints per column
--   1.15-1.17:   Level.Biomes, 1024 ints: 4x4x4 cells over y 0..255, index ((y>>2)*4 + (z>>2))*4 + (x>>2)
--   1.18+:       sections[].biomes = {palette = {names}, data = long array}: 64 cells of ceil(log2(#palette)) bits,
--                padded (fields do not span longs); no data when the palette has one entry
-- Tint colours are Minecraft's per-biome grass, foliage and water colours (the colour-map value at the biome's
-- temperature and downfall, or its fixed override); one class stands for biomes that look alike.
local torte = require "torte"
local data = torte.data

local M = {}

local function hex(h)
  return {((h >> 16) & 255) / 255, ((h >> 8) & 255) / 255, (h & 255) / 255}
end
local function tint(grass, foliage, water)
  return {grass = hex(grass), foliage = hex(foliage), water = hex(water)}
end

-- The reference class: blocks' own colours in minecraft.blocks are their look in plains.
M.REFERENCE = "plains"
M.TINTS = {
  plains = tint(0x91BD59, 0x77AB2F, 0x3F76E4),
  forest = tint(0x79C05A, 0x59AE30, 0x3F76E4),
  birch_forest = tint(0x88BB67, 0x6BA941, 0x3F76E4),
  dark_forest = tint(0x507A32, 0x59AE30, 0x3F76E4),
  jungle = tint(0x59C93C, 0x30BB0B, 0x3F76E4),
  swamp = tint(0x6A7039, 0x6A7039, 0x617B64),
  mangrove_swamp = tint(0x6A7039, 0x8DB127, 0x3A7A6A),
  taiga = tint(0x86B783, 0x68A464, 0x3F76E4),
  snowy = tint(0x80B497, 0x60A17B, 0x3D57D6),
  dry = tint(0xBFB755, 0xAEA42A, 0x3F76E4),          -- desert, savanna, the Nether
  badlands = tint(0x90814D, 0x9E814D, 0x3F76E4),
  mountains = tint(0x8AB689, 0x6DA36B, 0x3F76E4),    -- windswept hills, stony peaks, grove
  meadow = tint(0x83BB6D, 0x63A948, 0x0E4ECF),       -- meadow, cherry grove
  mushroom = tint(0x55C93F, 0x2BBB0F, 0x3F76E4),
  ocean = tint(0x8EB971, 0x71A74D, 0x3F76E4),        -- ocean, deep ocean, river, beach
  warm_ocean = tint(0x8EB971, 0x71A74D, 0x43D5EE),
  lukewarm_ocean = tint(0x8EB971, 0x71A74D, 0x45ADF2),
  cold_ocean = tint(0x8EB971, 0x71A74D, 0x3D57D6),
  frozen_ocean = tint(0x80B497, 0x60A17B, 0x3938C9),  -- frozen ocean and river
}
M.CLASSES = {}
for k in pairs(M.TINTS) do M.CLASSES[#M.CLASSES + 1] = k end
table.sort(M.CLASSES)
M.INDEX = {}  -- class -> 1..#CLASSES
for i, k in ipairs(M.CLASSES) do M.INDEX[k] = i end

-- Biome names (1.18+, plus the 1.13-1.17 names) -> class.
local BY_NAME = {}
local function names(class, list)
  for n in list:gmatch("%S+") do BY_NAME["minecraft:" .. n] = class end
end
names("plains", "plains sunflower_plains beach lush_caves dripstone_caves deep_dark the_void the_end "
      .. "small_end_islands end_midlands end_highlands end_barrens")
names("forest", "forest flower_forest wooded_hills")
names("birch_forest", "birch_forest old_growth_birch_forest birch_forest_hills tall_birch_forest tall_birch_hills")
names("dark_forest", "dark_forest dark_forest_hills")
names("jungle", "jungle sparse_jungle bamboo_jungle jungle_hills jungle_edge modified_jungle modified_jungle_edge "
      .. "bamboo_jungle_hills")
names("swamp", "swamp swamp_hills")
names("mangrove_swamp", "mangrove_swamp")
names("taiga", "taiga old_growth_pine_taiga old_growth_spruce_taiga taiga_hills taiga_mountains giant_tree_taiga "
      .. "giant_tree_taiga_hills giant_spruce_taiga giant_spruce_taiga_hills")
names("snowy", "snowy_plains snowy_taiga snowy_beach snowy_slopes frozen_peaks jagged_peaks ice_spikes grove "
      .. "snowy_tundra snowy_mountains snowy_taiga_hills snowy_taiga_mountains")
names("dry", "desert savanna savanna_plateau windswept_savanna desert_hills desert_lakes shattered_savanna "
      .. "shattered_savanna_plateau nether_wastes soul_sand_valley crimson_forest warped_forest basalt_deltas nether")
names("badlands", "badlands eroded_badlands wooded_badlands badlands_plateau wooded_badlands_plateau "
      .. "modified_badlands_plateau modified_wooded_badlands_plateau")
names("mountains", "windswept_hills windswept_gravelly_hills windswept_forest stony_peaks mountains "
      .. "gravelly_mountains wooded_mountains mountain_edge modified_gravelly_mountains extreme_hills stone_shore stony_shore")
names("meadow", "meadow cherry_grove")
names("mushroom", "mushroom_fields mushroom_field_shore")
names("ocean", "ocean deep_ocean river")
names("warm_ocean", "warm_ocean deep_warm_ocean")
names("lukewarm_ocean", "lukewarm_ocean deep_lukewarm_ocean")
names("cold_ocean", "cold_ocean deep_cold_ocean")
names("frozen_ocean", "frozen_ocean deep_frozen_ocean frozen_river")
M.BY_NAME = BY_NAME

-- Numeric biome ids (before 1.18) -> name.
local IDS = {
  [0] = "ocean", "plains", "desert", "mountains", "forest", "taiga", "swamp", "river", "nether", "the_end",
  "frozen_ocean", "frozen_river", "snowy_tundra", "snowy_mountains", "mushroom_fields", "mushroom_field_shore",
  "beach", "desert_hills", "wooded_hills", "taiga_hills", "mountain_edge", "jungle", "jungle_hills", "jungle_edge",
  "deep_ocean", "stone_shore", "snowy_beach", "birch_forest", "birch_forest_hills", "dark_forest", "snowy_taiga",
  "snowy_taiga_hills", "giant_tree_taiga", "giant_tree_taiga_hills", "wooded_mountains", "savanna",
  "savanna_plateau", "badlands", "wooded_badlands_plateau", "badlands_plateau", "small_end_islands", "end_midlands",
  "end_highlands", "end_barrens", "warm_ocean", "lukewarm_ocean", "cold_ocean", "deep_warm_ocean",
  "deep_lukewarm_ocean", "deep_cold_ocean", "deep_frozen_ocean",
  [127] = "the_void", [129] = "sunflower_plains", [130] = "desert_lakes", [131] = "gravelly_mountains",
  [132] = "flower_forest", [133] = "taiga_mountains", [134] = "swamp_hills", [140] = "ice_spikes",
  [149] = "modified_jungle", [151] = "modified_jungle_edge", [155] = "tall_birch_forest", [156] = "tall_birch_hills",
  [157] = "dark_forest_hills", [158] = "snowy_taiga_mountains", [160] = "giant_spruce_taiga",
  [161] = "giant_spruce_taiga_hills", [162] = "modified_gravelly_mountains", [163] = "shattered_savanna",
  [164] = "shattered_savanna_plateau", [165] = "eroded_badlands", [166] = "modified_wooded_badlands_plateau",
  [167] = "modified_badlands_plateau", [168] = "bamboo_jungle", [169] = "bamboo_jungle_hills",
  [170] = "soul_sand_valley", [171] = "crimson_forest", [172] = "warped_forest", [173] = "basalt_deltas",
  [174] = "dripstone_caves", [175] = "lush_caves",
}
M.NAMES_BY_ID = IDS

-- The class of a biome name or numeric id; unknown biomes (and "not generated") are plains.
function M.class_of(b)
  if math.type(b) == "integer" then
    local n = IDS[b]
    return n and BY_NAME["minecraft:" .. n] or M.REFERENCE
  end
  if type(b) == "string" then
    if not b:find(":", 1, true) then b = "minecraft:" .. b end
    return BY_NAME[b] or M.REFERENCE
  end
  return M.REFERENCE
end

local function classes_of(list, n, offset)
  local out, first, same = {}, nil, true
  for i = 1, n do
    local c = M.class_of(list[offset + i])
    out[i] = c
    if i == 1 then first = c elseif c ~= first then same = false end
  end
  if same then return {uniform = first} end
  return out
end

-- Per chunk: the column/cell classes of pre-1.18 chunks, computed once (cached by `level` table, beside it: a
-- key inside it could be met in a chunk's own NBT).
local legacy_cache = setmetatable({}, {__mode = "k"})
local function legacy_biomes(level)
  local b = level.Biomes
  local cached = legacy_cache[level]
  if cached ~= nil then return cached end
  local out = false
  if type(b) == "string" and #b == 256 then        -- bytes (<= 1.12)
    local r = classes_of({b:byte(1, 256)}, 256, 0)
    out = r.uniform and r or {columns = r}
  elseif type(b) == "table" and #b == 256 then     -- ints per column (1.13-1.14)
    local r = classes_of(b, 256, 0)
    out = r.uniform and r or {columns = r}
  elseif type(b) == "table" and #b == 1024 then    -- 4x4x4 cells (1.15-1.17), 64 layers of 16 cells
    out = {layers = {}}
    for layer = 0, 15 do  -- section cy covers cell layers 4cy..4cy+3 = entries 64cy+1..64cy+64
      local r = classes_of(b, 64, 64 * layer)
      out.layers[layer] = r.uniform and r or {cells = r}
    end
  end
  legacy_cache[level] = out
  return out
end

-- The tint classes of one section: nil, {uniform = c}, {cells = {64}} or {columns = {256}}.
function M.section(level, sec, cy)
  local sb = sec.biomes
  if type(sb) == "table" and type(sb.palette) == "table" then  -- 1.18+
    local p = sb.palette
    local n = #p
    if n == 0 then return nil end
    if n == 1 or sb.data == nil then return {uniform = M.class_of(p[1])} end
    local classes, same = {}, true
    for i = 1, n do
      classes[i] = M.class_of(p[i])
      if classes[i] ~= classes[1] then same = false end
    end
    if same then return {uniform = classes[1]} end
    local bits = 0
    while (1 << bits) < n do bits = bits + 1 end
    local ok, raw, counts = pcall(data.unpack_bits, sb.data, bits, 64, true)
    if not ok then return nil end  -- malformed biome data: leave the section untinted
    local cells, first, uniform = {}, nil, true
    for i = 1, 64 do
      local c = classes[string.unpack("<i2", raw, 2 * i - 1) + 1] or M.REFERENCE
      cells[i] = c
      if i == 1 then first = c elseif c ~= first then uniform = false end
    end
    if uniform then return {uniform = first} end
    return {cells = cells}
  end
  if level.Biomes == nil then return nil end
  local lb = legacy_biomes(level)
  if not lb then return nil end
  if lb.layers then
    if cy < 0 or cy > 15 then return nil end
    return lb.layers[cy]
  end
  return lb
end

-- The class at block (x, y, z) inside a section (0..15 each) given M.section's result.
function M.at(b, x, y, z)
  if not b then return nil end
  if b.uniform then return b.uniform end
  if b.cells then return b.cells[(y >> 2) * 16 + (z >> 2) * 4 + (x >> 2) + 1] end
  return b.columns[z * 16 + x + 1]
end

-- A selector for torte.data.map_int16 over a section's 4096 voxel ids (index (y*16 + z)*16 + x): one byte per
-- voxel, M.INDEX[class] - 1. Also returns the set of classes present {[class] = true}. Cached in `b`.
function M.selector(b)
  if b.selector then return b.selector, b.present end
  local present = {}
  local sel
  if b.uniform then
    present[b.uniform] = true
    sel = string.char(M.INDEX[b.uniform] - 1):rep(4096)
  elseif b.cells then
    local rows = {}
    for i, c in ipairs(b.cells) do present[c] = true end
    for y4 = 0, 3 do
      for z4 = 0, 3 do
        local r = {}
        for x4 = 0, 3 do r[x4 + 1] = string.char(M.INDEX[b.cells[y4 * 16 + z4 * 4 + x4 + 1]] - 1):rep(4) end
        rows[y4 * 4 + z4] = table.concat(r)
      end
    end
    local out = {}
    for y = 0, 15 do
      for z = 0, 15 do out[y * 16 + z + 1] = rows[(y >> 2) * 4 + (z >> 2)] end
    end
    sel = table.concat(out)
  else
    local layer = {}
    for i, c in ipairs(b.columns) do
      present[c] = true
      layer[i] = string.char(M.INDEX[c] - 1)
    end
    sel = table.concat(layer):rep(16)
  end
  b.selector, b.present = sel, present
  return sel, present
end

return M
