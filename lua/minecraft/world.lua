-- minecraft.world: loads the blocks of a Minecraft Java world's region files into 16^3 sections of 16-bit voxel
-- ids, in Minecraft's section order (index = (y * 16 + z) * 16 + x), handing each section to a sink.
--
--   local world = require "minecraft.world"
--   local stats = world.load{
--     dir = "saves/World1",          -- a folder of r.X.Z.mca files, or a world folder with region/ inside
--     files = nil,                   -- or an explicit list of region files
--     box = {x0, y0, z0, x1, y1, z1},-- optional: only blocks with x0 <= x < x1 etc. (world block coordinates)
--     sink = function(cx, cy, cz, ids, non_air) end,  -- ids: 8192-byte string of little-endian int16 voxel ids
--     registry = blocks.registry(),  -- maps block states to voxel ids (minecraft.blocks)
--     skip_bad_chunks = false,       -- true: a corrupt chunk is counted and skipped instead of an error
--     progress = true,               -- percent of chunks on stderr
--     probes = {{x, y, z}, ...},     -- optional: the raw block at these positions ("minecraft:stone" or "1:0")
--     emitters = true,               -- collect positions of emitting blocks (stats.emitters)
--   }
--   stats: files, chunks, full, not_full, bad, bad_messages, sections, non_air, data_versions {dv = count}
--          (0 = no DataVersion), formats {name = chunks}, statuses {status = chunks}, unknown, unknown_blocks,
--          probes {[i] = raw block}, probe_biomes {[i] = tint class there}, bounds {lo = {x,y,z}, hi = {x,y,z}}
--          (voxels loaded), emitters, connected_sections (pre-1.13 sections whose fences etc. were joined), seconds
--
-- Biome tints: blocks whose colour follows the biome (registry.tint_kind) become the registry's variant for the
-- tint class at their position (minecraft.biomes reads the biome data of every format). Connections: 1.13+ block
-- states name them; pre-1.13 sections holding fences, walls or panes are handed to the sink at the end of the
-- load, once M.connect_section has joined those blocks to their neighbours (in any loaded section).
--
-- Block storage formats handled (the chunk NBT layout by version):
--   legacy:     Level.Sections[].Blocks (byte per block) + Add (high nibble, optional) + Data (nibble); <= 1.12
--   palette:    Level.Sections[].Palette + BlockStates; entries span longs before DataVersion 2529 (20w17a, 1.16)
--   root:       sections[].block_states.{palette, data} at the chunk root, y from -64 (1.18+)
-- Chunks whose status is not full are skipped ("full", "minecraft:full", 1.13's "postprocessed"/"fullchunk";
-- pre-1.13 chunks have no status and count as full).
local torte = require "torte"
local region = require "minecraft.region"
local blocks = require "minecraft.blocks"
local biomes = require "minecraft.biomes"
local data = torte.data

local M = {}

M.FULL_STATUS = {full = true, ["minecraft:full"] = true, postprocessed = true, fullchunk = true,
                 ["minecraft:postprocessed"] = true}
local SPANNING_BEFORE = 2529  -- DataVersion of 20w17a: from here on, entries do not span longs

-- Region files of a folder (or its region/ subfolder), sorted.
function M.region_files(dir)
  local function list(d)
    local files = {}
    for _, name in ipairs(data.list_dir(d) or {}) do
      if region.coords(name) then files[#files + 1] = d .. "/" .. name end
    end
    return files
  end
  local files = list(dir)
  if #files == 0 then files = list(dir .. "/region") end
  return files
end

-- The keys of a table in ascending order (numbers, or strings): pairs() order varies from run to run (Lua
-- seeds string hashing per state), and ids and materials handed out while iterating must not.
local function sorted_keys(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys)
  return keys
end
M.sorted_keys = sorted_keys

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
M.printable = printable

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

-- Hands a decoded section to the sink: clipped to the box, emitters collected, bounds grown.
local function deliver(opt, stats, cx, cy, cz, ids, non_air, by_id)
  local ox, oy, oz = cx * 16, cy * 16, cz * 16
  local box = opt.box
  if box then ids = clip(ids, ox, oy, oz, box) end
  if not ids or not (non_air > 0 or by_id[0] ~= 4096) then return end
  -- emitters: positions of blocks whose id emits
  local reg = opt.registry
  if opt.emitters then
    for _, id in ipairs(sorted_keys(by_id)) do  -- in id order: the list is capped at max_emitters
      if id ~= 0 and reg:emission(id) and #stats.emitters < (opt.max_emitters or 4096) then
        local init = 1
        local pat = string.pack("<i2", id)
        while true do
          local at = ids:find(pat, init, true)
          if not at then break end
          if at % 2 == 1 then
            local i = (at - 1) // 2
            local e = stats.emitters
            if #e >= (opt.max_emitters or 4096) then break end
            e[#e + 1] = {ox + (i & 15), oy + (i >> 8), oz + ((i >> 4) & 15), id}
            init = at + 2
          else
            init = at + 1
          end
        end
      end
    end
  end
  local b = stats.bounds
  if ox < b.lo[1] then b.lo[1] = ox end
  if oy < b.lo[2] then b.lo[2] = oy end
  if oz < b.lo[3] then b.lo[3] = oz end
  if ox + 16 > b.hi[1] then b.hi[1] = ox + 16 end
  if oy + 16 > b.hi[2] then b.hi[2] = oy + 16 end
  if oz + 16 > b.hi[3] then b.hi[3] = oz + 16 end
  if opt.sink then opt.sink(cx, cy, cz, ids, non_air) end
end

-- Loads one chunk's root compound; updates stats, calls the sink. Errors name `where`. Every section is decoded
-- before anything is counted or handed on, so a chunk that fails (and is skipped) leaves no trace but its error.
local function load_chunk(root, c, opt, stats, where)
  local reg = opt.registry
  local dv = root.DataVersion
  if dv ~= nil and math.type(dv) ~= "integer" then error(where .. ": DataVersion is not an integer", 0) end
  dv = dv or 0
  local level = root.Level
  local status, sections
  if level ~= nil and type(level) ~= "table" then
    error(("%s: Level is %s, not a compound"):format(where, nbt_type(level)), 0)
  end
  if level then
    status = level.Status
    sections = level.Sections
    if status == nil then status = "full" end  -- pre-1.13: no status
  else
    level = root
    status = root.Status
    sections = root.sections
  end
  local function count_version()
    stats.data_versions[dv] = (stats.data_versions[dv] or 0) + 1
    stats.statuses[tostring(status)] = (stats.statuses[tostring(status)] or 0) + 1
  end
  if not M.FULL_STATUS[status] then
    count_version()
    stats.not_full = stats.not_full + 1
    return
  end
  if sections ~= nil and type(sections) ~= "table" then
    error(("%s: the section list is %s, not a list"):format(where, nbt_type(sections)), 0)
  end
  -- The chunk is where the region header puts it (as in Minecraft): a wrong xPos/zPos cannot move it.
  local cx, cz = c.x, c.z
  local decoded = {}
  for si = 1, sections and #sections or 0 do
    local sec = sections[si]
    if type(sec) ~= "table" then
      error(("%s: section %d is %s, not a compound"):format(where, si, nbt_type(sec)), 0)
    end
    local cy = sec.Y
    if math.type(cy) ~= "integer" then error(("%s: section %d has no Y"):format(where, si), 0) end
    if cy < -128 or cy > 127 then  -- a byte in every format
      error(("%s: section %d has Y=%d, outside -128..127"):format(where, si, cy), 0)
    end
    local swhere = ("%s, section Y=%d"):format(where, cy)
    local ids, non_air, by_id, map, packed
    local kind
    local function biome_fn() return biomes.section(level, sec, cy) end
    if sec.block_states ~= nil then
      local bs = sec.block_states
      if type(bs) ~= "table" or type(bs.palette) ~= "table" then error(swhere .. ": block_states has no palette", 0) end
      ids, non_air, by_id, map, packed = palette_section(bs.palette, bs.data, dv, reg, swhere, biome_fn)
      kind = "root/block_states"
    elseif sec.Palette ~= nil then
      ids, non_air, by_id, map, packed = palette_section(sec.Palette, sec.BlockStates, dv, reg, swhere, biome_fn)
      kind = dv >= SPANNING_BEFORE and "Level/Palette (padded)" or "Level/Palette (spanning)"
    elseif sec.Blocks ~= nil then
      ids, non_air, by_id = legacy_section(sec, reg, swhere)
      ids = tint_section(ids, by_id, reg, biome_fn)
      kind = "Level/Blocks"
    end
    if ids then
      decoded[#decoded + 1] = {sec = sec, cy = cy, ids = ids, non_air = non_air, by_id = by_id, packed = packed,
                               kind = kind, biome_fn = biome_fn}
    end
  end
  count_version()
  stats.full = stats.full + 1
  local format
  for _, d in ipairs(decoded) do
    local sec, cy, ids, non_air, by_id, packed, kind = d.sec, d.cy, d.ids, d.non_air, d.by_id, d.packed, d.kind
    format = kind
    stats.sections = stats.sections + 1
    stats.non_air = stats.non_air + non_air
    for id, n in pairs(by_id) do reg:count_unknown(id, n) end
    if opt.probes then
      for pi, p in ipairs(opt.probes) do
        if p[1] // 16 == cx and p[2] // 16 == cy and p[3] // 16 == cz then
          local i = ((p[2] & 15) << 8) | ((p[3] & 15) << 4) | (p[1] & 15)
          if kind == "Level/Blocks" then
            stats.probes[pi] = raw_legacy(sec, i)
          else
            local palette = sec.block_states and sec.block_states.palette or sec.Palette
            local index = 0
            if packed then
              local raw = data.unpack_bits(packed[1], packed[2], 4096, packed[3])
              index = string.unpack("<i2", raw, 2 * i + 1)
            end
            stats.probes[pi] = palette[index + 1].Name
          end
          stats.probe_biomes[pi] = biomes.at(d.biome_fn(), p[1] & 15, p[2] & 15, p[3] & 15)
        end
      end
    end
    if kind == "Level/Blocks" then
      local key = cx .. "," .. cy .. "," .. cz
      -- Pre-1.13 block states carry no connections: fences, walls and panes are joined to their neighbours once
      -- every section is loaded (M.connect_section); until then the loader keeps every legacy section.
      local legacy = stats.legacy_sections
      legacy[key] = ids
      local family = reg.family
      for id in pairs(by_id) do
        if family[id] then
          stats.pending[#stats.pending + 1] = {cx, cy, cz, non_air, by_id}
          ids = nil
          break
        end
      end
    end
    if ids then deliver(opt, stats, cx, cy, cz, ids, non_air, by_id) end
  end
  if format then stats.formats[format] = (stats.formats[format] or 0) + 1 end
end

-- The id at block (x, y, z) of the world in `sections` ("cx,cy,cz" -> id strings); 0 outside.
local function id_at(sections, x, y, z)
  local s = sections[(x // 16) .. "," .. (y // 16) .. "," .. (z // 16)]
  if not s then return 0 end
  return (string.unpack("<i2", s, 2 * (((y & 15) << 8) | ((z & 15) << 4) | (x & 15)) + 1))
end
M.id_at = id_at

-- Joins the fences, walls, glass panes and iron bars of pre-1.13 sections (`sections`: "cx,cy,cz" -> ids) to their
-- neighbours as Minecraft 1.12 draws them: a side connects to the same family (wooden fences with each other,
-- nether brick fences, panes with iron bars, walls), to fence gates (fences and walls), and to solid cubes. A wall
-- shows its post unless it runs straight (north-south or east-west only) with air above. Returns the new ids
-- string of the section at (cx, cy, cz).
function M.connect_section(sections, cx, cy, cz, reg)
  local ids = sections[cx .. "," .. cy .. "," .. cz]
  local family = reg.family
  local v = {string.unpack(PACK4096, ids)}
  local ox, oy, oz = cx * 16, cy * 16, cz * 16
  local changed = false
  local function glass(nid)
    local e = reg.entries[nid]
    return nid > 0 and e ~= nil and e.def ~= nil and e.def.mat == "glass"
  end
  local function attaches(f, nid)
    if nid == 0 then return false end
    local nf = family[nid]
    if nf then
      if nf == f then return true end
      if nf == "gate" then return f ~= "pane" end
      return false
    end
    if f == "pane" and glass(nid) then return true end  -- panes join glass blocks, fences and walls do not
    return reg:solid(nid)
  end
  for i = 1, 4096 do
    local id = v[i]
    local f = family[id]
    if f and f ~= "gate" then
      local x, y, z = ox + ((i - 1) & 15), oy + ((i - 1) >> 8), oz + (((i - 1) >> 4) & 15)
      local c = {north = attaches(f, id_at(sections, x, y, z - 1)), south = attaches(f, id_at(sections, x, y, z + 1)),
                 west = attaches(f, id_at(sections, x - 1, y, z)), east = attaches(f, id_at(sections, x + 1, y, z))}
      if f == "wall" then
        local straight = (c.north and c.south and not c.east and not c.west)
                         or (c.east and c.west and not c.north and not c.south)
        c.up = not straight or id_at(sections, x, y + 1, z) ~= 0
      end
      local nid = reg:connected(id, c)
      if nid ~= id then
        v[i] = nid
        changed = true
      end
    end
  end
  if not changed then return ids end
  return string.pack(PACK4096, table.unpack(v, 1, 4096))
end

-- Keeps only the top of each body of water: `sections` maps "cx,cy,cz" to id strings (as given to a sink); every
-- voxel with a water id that has water right above it becomes empty. `water` is one id or a set {[id] = true}
-- (water has one id per biome tint: Registry:ids_of). Returns the number of voxels emptied and the number of
-- surface cells kept per id.
-- (Rays then cross one water surface, not one interface per block.)
function M.water_surfaces(sections, water)
  if type(water) ~= "table" then
    if not water or water == 0 then return 0, {} end
    water = {[water] = true}
  end
  local pats = {}
  for _, id in ipairs(sorted_keys(water)) do
    if id ~= 0 then pats[#pats + 1] = string.pack("<i2", id) end
  end
  if #pats == 0 then return 0, {} end
  local function has_water(ids)
    for _, pat in ipairs(pats) do
      if ids:find(pat, 1, true) then return true end
    end
    return false
  end
  local emptied, surface = 0, {}
  -- Work on the original strings for "above" lookups, write new strings afterwards.
  local out = {}
  for key, ids in pairs(sections) do
    if has_water(ids) then
      local cx, cy, cz = key:match("^(%-?%d+),(%-?%d+),(%-?%d+)$")
      local above_ids = sections[cx .. "," .. (tonumber(cy) + 1) .. "," .. cz]
      local v = {string.unpack(PACK4096, ids)}
      local av = above_ids and has_water(above_ids) and {string.unpack(PACK4096, above_ids)} or nil
      local changed = false
      for i = 1, 4096 do
        if water[v[i]] then
          local up
          if i <= 3840 then up = v[i + 256] else up = av and av[i - 3840] end
          if water[up] then
            v[i] = 0
            changed = true
            emptied = emptied + 1
          else
            surface[v[i]] = (surface[v[i]] or 0) + 1
          end
        end
      end
      if changed then v[4097] = nil out[key] = string.pack(PACK4096, table.unpack(v, 1, 4096)) end
    end
  end
  -- Deep cells were decided from the original data (a cell stays deep even when the one above was emptied).
  for key, ids in pairs(out) do sections[key] = ids end
  return emptied, surface
end

function M.load(opt)
  local t0 = torte.clock()
  if type(opt) ~= "table" then error("minecraft.world.load expects a table of options", 2) end
  opt.registry = opt.registry or blocks.registry()
  if opt.files == nil and type(opt.dir) ~= "string" then
    error("minecraft.world.load: 'dir' (a folder name) or 'files' is required", 2)
  end
  local files = opt.files
  if files ~= nil then
    if type(files) ~= "table" or #files == 0 then
      error("minecraft.world.load: 'files' must be a non-empty list of region file names", 2)
    end
    for i, f in ipairs(files) do
      if type(f) ~= "string" then error(("minecraft.world.load: files[%d] is not a file name"):format(i), 2) end
    end
  else
    files = M.region_files(opt.dir)
    if #files == 0 then
      error(("minecraft.world.load: no region files (r.X.Z.mca) in '%s' or its region/ folder"):format(opt.dir), 2)
    end
  end
  local stats = {files = #files, chunks = 0, full = 0, not_full = 0, bad = 0, bad_messages = {}, sections = 0,
                 non_air = 0, data_versions = {}, statuses = {}, formats = {}, probes = {}, probe_biomes = {}, emitters = {},
                 pending = {}, legacy_sections = {},
                 bounds = {lo = {math.huge, math.huge, math.huge}, hi = {-math.huge, -math.huge, -math.huge}}}
  local box = opt.box
  -- Open every file and list the chunks first, so progress is a percentage of all chunks.
  local regions, total = {}, 0
  for _, f in ipairs(files) do
    local r = region.open(f)
    local list = {}
    for _, c in ipairs(r:chunks()) do
      if not box or (c.x * 16 < box[4] and c.x * 16 + 16 > box[1] and c.z * 16 < box[6] and c.z * 16 + 16 > box[3]) then
        list[#list + 1] = c
      end
    end
    regions[#regions + 1] = {r = r, list = list}
    total = total + #list
  end
  local done, last_pct = 0, -1
  local show = opt.progress and total > 0
  for _, rr in ipairs(regions) do
    local r = rr.r
    for _, c in ipairs(rr.list) do
      stats.chunks = stats.chunks + 1
      local ok, err = pcall(function()
        local root = r:read(c)
        load_chunk(root, c, opt, stats, r:where(c))
      end)
      if not ok then
        err = region.chunk_error(err, r:where(c))
        if not opt.skip_bad_chunks then error(err, 0) end
        stats.bad = stats.bad + 1
        stats.bad_messages[#stats.bad_messages + 1] = err
      end
      done = done + 1
      if show then
        local pct = done * 100 // total
        if pct ~= last_pct and (pct % 10 == 0 or pct == 100) then
          io.stderr:write(("minecraft: loading %s: %d%% of %d chunks\n"):format(opt.dir or files[1], pct, total))
          last_pct = pct
        end
      end
    end
    r.bytes = nil  -- let the file's memory go
  end
  -- Pre-1.13 fences, walls and panes: joined to their neighbours now that every section is here.
  for _, p in ipairs(stats.pending) do
    local ids = M.connect_section(stats.legacy_sections, p[1], p[2], p[3], opt.registry)
    deliver(opt, stats, p[1], p[2], p[3], ids, p[4], p[5])
  end
  stats.connected_sections = #stats.pending
  stats.pending, stats.legacy_sections = nil, nil
  stats.unknown = opt.registry.unknown
  stats.unknown_blocks = opt.registry.unknown_blocks
  stats.registry = opt.registry
  stats.seconds = torte.clock() - t0
  if stats.bad > 0 and opt.progress then
    io.stderr:write(("minecraft: skipped %d bad chunk%s; first: %s\n"):format(stats.bad, stats.bad == 1 and "" or "s",
                                                                           stats.bad_messages[1]))
  end
  return stats
end

return M
