-- minecraft.section: decodes one chunk section's blocks into 4096 voxel ids (16-bit, Minecraft's section order,
-- index = (y * 16 + z) * 16 + x), from either storage format, with biome tints applied; and the small helpers
-- minecraft.world shares with it. minecraft.world walks regions and chunks and hands the sections on.
--   palette_section(palette, states, dv, reg, where, biome_fn) -> ids, non_air, counts_by_id, map, raw | nil
--   legacy_section(sec, reg, where) -> ids, non_air, counts_by_id          (pre-1.13 Blocks/Data/Add arrays)
--   raw_legacy(sec, i) -> "id:data" of block i;  tint_section(ids, by_id, reg, biome_fn) -> ids
--   clip(ids, ox, oy, oz, box) -> ids | nil;  uniform(id) -> ids;  PACK4096 (string.pack format of a section);
--   SPANNING_BEFORE (the DataVersion from which palette entries no longer span longs)
local torte = require "torte"
local region = require "minecraft.region"
local blocks = require "minecraft.blocks"
local biomes = require "minecraft.biomes"
local data = torte.data

local M = {}

local SPANNING_BEFORE = 2529  -- DataVersion of 20w17a: from here on, entries do not span longs

-- The keys of a table in ascending order (numbers, or strings): pairs() order varies from run to run (Lua
-- seeds string hashing per state), and ids and materials handed out while iterating must not.
local function sorted_keys(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys)
  return keys
end

-- What an NBT value decoded to, for messages ("palette entry 1 is a number, not a compound").
local function nbt_type(v)
  if type(v) == "userdata" then return "a long array" end
  if type(v) == "table" then
    if #v > 0 then return "a list" end
    return next(v) == nil and "an empty list or compound" or "a compound"
  end
  if type(v) == "string" then return "a string or byte array" end
  return "a " .. type(v)
end

-- A name from a chunk, safe for a one-line message (control bytes escaped).
local function printable(name)
  return (name:gsub("%c", function(ch) return ("\\x%02x"):format(ch:byte()) end))
end

local function ceil_log2(n)
  local b = 0
  while (1 << b) < n do b = b + 1 end
  return b
end

local UNIFORM = {}
local function uniform(id)
  local s = UNIFORM[id]
  if not s then
    s = string.pack("<i2", id):rep(4096)
    UNIFORM[id] = s
  end
  return s
end

local ZERO_ROW = ("\0"):rep(32)
-- Zeroes the voxels of a section (at block origin ox, oy, oz) outside the box.
local function clip(ids, ox, oy, oz, b)
  local x0, x1 = math.max(b[1] - ox, 0), math.min(b[4] - ox, 16)
  local y0, y1 = math.max(b[2] - oy, 0), math.min(b[5] - oy, 16)
  local z0, z1 = math.max(b[3] - oz, 0), math.min(b[6] - oz, 16)
  if x0 >= x1 or y0 >= y1 or z0 >= z1 then return nil end
  if x0 == 0 and y0 == 0 and z0 == 0 and x1 == 16 and y1 == 16 and z1 == 16 then return ids end
  local rows = {}
  local pre, post = ("\0"):rep(2 * x0), ("\0"):rep(2 * (16 - x1))
  for y = 0, 15 do
    for z = 0, 15 do
      local r = y * 16 + z
      if y < y0 or y >= y1 or z < z0 or z >= z1 then
        rows[r + 1] = ZERO_ROW
      else
        rows[r + 1] = pre .. ids:sub(r * 32 + 2 * x0 + 1, r * 32 + 2 * x1) .. post
      end
    end
  end
  return table.concat(rows)
end

local PACK4096 = "<" .. ("i2"):rep(4096)

-- Biome tints of a section whose blocks vary in biome: every voxel with an id in `tintable` becomes its variant
-- for the class at its position (`b`: minecraft.biomes.section's result), in C++ (torte.data.map_int16).
local function tint_voxels(ids, tintable, b, reg)
  local sel, present = biomes.selector(b)
  local maps = {}
  local tinted = sorted_keys(tintable)  -- reg:tinted hands out new ids: in a fixed order
  for _, c in ipairs(sorted_keys(present)) do
    local m = {}
    for _, id in ipairs(tinted) do m[id] = reg:tinted(id, c) end
    maps[biomes.INDEX[c]] = m
  end
  return data.map_int16(ids, maps, sel)
end

-- Applies biome tints to a decoded section (ids string, counts by id); returns the new ids string.
local function tint_section(ids, by_id, reg, biome_fn)
  local tintable
  for id in pairs(by_id) do
    if reg.tint_kind[id] then
      tintable = tintable or {}
      tintable[id] = true
    end
  end
  if not tintable then return ids end
  local b = biome_fn()
  if not b then return ids end
  if b.uniform then
    local remap = {}
    for _, id in ipairs(sorted_keys(tintable)) do remap[id] = reg:tinted(id, b.uniform) end
    return data.map_int16(ids, remap)
  end
  return tint_voxels(ids, tintable, b, reg)
end

-- Decodes one section into (ids, non_air, counts_by_id); `reg` maps states to voxel ids; `biome_fn()` gives the
-- section's biomes (minecraft.biomes.section), asked only when a block of the palette is tinted.
-- Returns nil for sections without blocks (light-only).
local MAX_PALETTE = 4096  -- one entry per block of the section at most
local function palette_section(palette, states, dv, reg, where, biome_fn)
  if type(palette) ~= "table" then error(where .. ": the palette is not a list", 0) end
  local n = #palette
  if n == 0 then return nil end
  if n > MAX_PALETTE then
    error(("%s: the palette has %d entries (a section holds %d blocks)"):format(where, n, MAX_PALETTE), 0)
  end
  local map, air = {}, {}
  local tinted, tint_kind = nil, reg.tint_kind
  for i = 1, n do
    local e = palette[i]
    if type(e) ~= "table" then
      error(("%s: palette entry %d is %s, not a compound"):format(where, i, nbt_type(e)), 0)
    end
    local name = e.Name
    if type(name) ~= "string" then error(where .. ": palette entry " .. i .. " has no Name", 0) end
    local props = e.Properties
    if props ~= nil and type(props) ~= "table" then
      error(("%s: palette entry %d (%s): Properties is %s, not a compound"):format(where, i, printable(name),
                                                                                   nbt_type(props)), 0)
    end
    local id = reg:state(name, props)
    map[i] = id
    air[i] = blocks.AIR[name] or false
    if tint_kind[id] then
      tinted = tinted or {}
      tinted[#tinted + 1] = i
    end
  end
  local per_voxel  -- biomes that vary inside the section: tinted after unpacking
  if tinted then
    local b = biome_fn()
    if b and b.uniform then
      for _, i in ipairs(tinted) do map[i] = reg:tinted(map[i], b.uniform) end
    elseif b then
      per_voxel = b
    end
  end
  if states == nil or (n == 1 and (type(states) ~= "userdata" or #states == 0)) then
    if n > 1 then error(where .. (": %d palette entries but no block data"):format(n), 0) end
    local ids = uniform(map[1])
    if per_voxel then ids = tint_voxels(ids, {[map[1]] = true}, per_voxel, reg) end
    return ids, air[1] and 0 or 4096, {[map[1]] = 4096}, map, nil
  end
  if type(states) ~= "userdata" then
    error(("%s: the block data is %s, not a long array"):format(where, nbt_type(states)), 0)
  end
  local bits = math.max(4, ceil_log2(n))
  local padded = dv >= SPANNING_BEFORE
  local ok, ids, counts = pcall(data.unpack_bits, states, bits, 4096, padded, map)
  if not ok then error(where .. ": " .. region.bare_error(ids), 0) end
  local non_air, by_id = 0, {}
  for i, c in ipairs(counts) do  -- counts[i]: voxels using palette entry i
    if c > 0 then
      if i > n then error(where .. (": block index %d is outside the palette of %d"):format(i - 1, n), 0) end
      if not air[i] then non_air = non_air + c end
      by_id[map[i]] = (by_id[map[i]] or 0) + c
    end
  end
  if per_voxel then
    local tintable = {}
    for _, i in ipairs(tinted) do tintable[map[i]] = true end
    ids = tint_voxels(ids, tintable, per_voxel, reg)
  end
  return ids, non_air, by_id, map, {states, bits, padded}
end
local function legacy_section(sec, reg, where)
  local bl, dt, add = sec.Blocks, sec.Data, sec.Add
  if type(bl) ~= "string" or #bl ~= 4096 then error(where .. ": Blocks is not a 4096-byte array", 0) end
  if type(dt) ~= "string" or #dt ~= 2048 then error(where .. ": Data is not a 2048-byte array", 0) end
  if add ~= nil and (type(add) ~= "string" or #add ~= 2048) then error(where .. ": Add is not a 2048-byte array", 0) end
  local b = {bl:byte(1, 4096)}
  local d = {dt:byte(1, 2048)}
  local a = add and {add:byte(1, 2048)}
  local out, by_id, non_air = {}, {}, 0
  local cache = reg.legacy_cache
  for k = 1, 4095, 2 do
    local j = (k + 1) >> 1
    local dd = d[j]
    local b1, b2 = b[k], b[k + 1]
    if a then
      local aa = a[j]
      b1, b2 = b1 | ((aa & 15) << 8), b2 | ((aa >> 4) << 8)
    end
    local k1, k2 = b1 * 16 + (dd & 15), b2 * 16 + (dd >> 4)
    local v1 = cache[k1] or reg:legacy(b1, dd & 15)
    local v2 = cache[k2] or reg:legacy(b2, dd >> 4)
    out[k], out[k + 1] = v1, v2
    if b1 ~= 0 then non_air = non_air + 1 end
    if b2 ~= 0 then non_air = non_air + 1 end
    by_id[v1] = (by_id[v1] or 0) + 1
    by_id[v2] = (by_id[v2] or 0) + 1
  end
  return string.pack(PACK4096, table.unpack(out)), non_air, by_id
end

local function raw_legacy(sec, i)
  local id = sec.Blocks:byte(i + 1)
  if sec.Add then id = id | (((sec.Add:byte((i >> 1) + 1) >> (4 * (i & 1))) & 15) << 8) end
  return ("%d:%d"):format(id, (sec.Data:byte((i >> 1) + 1) >> (4 * (i & 1))) & 15)
end

M.sorted_keys = sorted_keys
M.nbt_type = nbt_type
M.printable = printable
M.uniform = uniform
M.clip = clip
M.PACK4096 = PACK4096
M.tint_section = tint_section
M.palette_section = palette_section
M.legacy_section = legacy_section
M.raw_legacy = raw_legacy
M.SPANNING_BEFORE = SPANNING_BEFORE

return M
