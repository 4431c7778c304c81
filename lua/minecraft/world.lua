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
local section = require "minecraft.section"
local sorted_keys, nbt_type, clip, PACK4096 = section.sorted_keys, section.nbt_type, section.clip, section.PACK4096
local tint_section, palette_section = section.tint_section, section.palette_section
local legacy_section, raw_legacy = section.legacy_section, section.raw_legacy
local SPANNING_BEFORE = section.SPANNING_BEFORE

local M = {}
M.sorted_keys, M.printable = sorted_keys, section.printable  -- for scripts (scenes/minecraft.lua)

M.FULL_STATUS = {full = true, ["minecraft:full"] = true, postprocessed = true, fullchunk = true,
                 ["minecraft:postprocessed"] = true}

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
