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
--          probes {[i] = raw block}, bounds {lo = {x,y,z}, hi = {x,y,z}} (voxels loaded), emitters, seconds
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

-- Decodes one section into (ids, non_air, counts_by_id); `reg` maps states to voxel ids.
-- Returns nil for sections without blocks (light-only).
local function palette_section(palette, states, dv, reg, where)
  local n = #palette
  if n == 0 then return nil end
  local map, air = {}, {}
  for i = 1, n do
    local e = palette[i]
    local name = e.Name
    if type(name) ~= "string" then error(where .. ": palette entry " .. i .. " has no Name", 0) end
    map[i] = reg:state(name, e.Properties)
    air[i] = blocks.AIR[name] or false
  end
  if states == nil or (n == 1 and (type(states) ~= "userdata" or #states == 0)) then
    if n > 1 then error(where .. (": %d palette entries but no block data"):format(n), 0) end
    return uniform(map[1]), air[1] and 0 or 4096, {[map[1]] = 4096}, map, nil
  end
  if type(states) ~= "userdata" then error(where .. ": block data is not a long array", 0) end
  local bits = math.max(4, ceil_log2(n))
  local padded = dv >= SPANNING_BEFORE
  local ok, ids, counts = pcall(data.unpack_bits, states, bits, 4096, padded, map)
  if not ok then error(where .. ": " .. region.bare_error(ids), 0) end
  local non_air, by_id = 0, {}
  for i, c in pairs(counts) do
    if c > 0 then
      if i > n then error(where .. (": block index %d is outside the palette of %d"):format(i - 1, n), 0) end
      if not air[i] then non_air = non_air + c end
      by_id[map[i]] = (by_id[map[i]] or 0) + c
    end
  end
  return ids, non_air, by_id, map, {states, bits, padded}
end

local PACK4096 = "<" .. ("i2"):rep(4096)
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

-- Loads one chunk's root compound; updates stats, calls the sink. Errors name `where`.
local function load_chunk(root, c, opt, stats, where)
  local reg = opt.registry
  local dv = root.DataVersion
  if dv ~= nil and math.type(dv) ~= "integer" then error(where .. ": DataVersion is not an integer", 0) end
  dv = dv or 0
  local level = root.Level
  local status, sections, format
  if type(level) == "table" then
    status = level.Status
    sections = level.Sections
    if status == nil then status = "full" end  -- pre-1.13: no status
  else
    level = root
    status = root.Status
    sections = root.sections
  end
  stats.data_versions[dv] = (stats.data_versions[dv] or 0) + 1
  stats.statuses[tostring(status)] = (stats.statuses[tostring(status)] or 0) + 1
  if not M.FULL_STATUS[status] then
    stats.not_full = stats.not_full + 1
    return
  end
  stats.full = stats.full + 1
  if sections == nil then return end
  if type(sections) ~= "table" then error(where .. ": the section list is not a list", 0) end
  local cx, cz = level.xPos, level.zPos
  if math.type(cx) ~= "integer" or math.type(cz) ~= "integer" then cx, cz = c.x, c.z end
  local box = opt.box
  for si = 1, #sections do
    local sec = sections[si]
    local cy = sec.Y
    if math.type(cy) ~= "integer" then error(("%s: section %d has no Y"):format(where, si), 0) end
    local swhere = ("%s, section Y=%d"):format(where, cy)
    local ids, non_air, by_id, map, packed
    local kind
    if sec.block_states ~= nil then
      local bs = sec.block_states
      if type(bs) ~= "table" or type(bs.palette) ~= "table" then error(swhere .. ": block_states has no palette", 0) end
      ids, non_air, by_id, map, packed = palette_section(bs.palette, bs.data, dv, reg, swhere)
      kind = "root/block_states"
    elseif sec.Palette ~= nil then
      ids, non_air, by_id, map, packed = palette_section(sec.Palette, sec.BlockStates, dv, reg, swhere)
      kind = dv >= SPANNING_BEFORE and "Level/Palette (padded)" or "Level/Palette (spanning)"
    elseif sec.Blocks ~= nil then
      ids, non_air, by_id = legacy_section(sec, reg, swhere)
      kind = "Level/Blocks"
    end
    if ids then
      format = kind
      stats.sections = stats.sections + 1
      stats.non_air = stats.non_air + non_air
      for id, n in pairs(by_id) do reg:count_unknown(id, n) end
      local ox, oy, oz = cx * 16, cy * 16, cz * 16
      -- probes
      if opt.probes then
        for pi, p in ipairs(opt.probes) do
          if p[1] // 16 == cx and p[2] // 16 == cy and p[3] // 16 == cz then
            local i = ((p[2] & 15) << 8) | ((p[3] & 15) << 4) | (p[1] & 15)
            if sec.Blocks ~= nil and sec.block_states == nil and sec.Palette == nil then
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
          end
        end
      end
      if box then ids = clip(ids, ox, oy, oz, box) end
      if ids and (non_air > 0 or by_id[0] ~= 4096) then
        -- emitters: positions of blocks whose id emits
        if opt.emitters then
          for id in pairs(by_id) do
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
    end
  end
  if format then stats.formats[format] = (stats.formats[format] or 0) + 1 end
end

-- Keeps only the top of each body of water: `sections` maps "cx,cy,cz" to id strings (as given to a sink); every
-- voxel with id `water` that has `water` right above it becomes empty. Returns the number of voxels emptied.
-- (Rays then cross one water surface, not one interface per block.)
function M.water_surfaces(sections, water)
  if not water or water == 0 then return 0 end
  local pat = string.pack("<i2", water)
  local emptied = 0
  -- Work on the original strings for "above" lookups, write new strings afterwards.
  local out = {}
  for key, ids in pairs(sections) do
    if ids:find(pat, 1, true) then
      local cx, cy, cz = key:match("^(%-?%d+),(%-?%d+),(%-?%d+)$")
      local above_ids = sections[cx .. "," .. (tonumber(cy) + 1) .. "," .. cz]
      local v = {string.unpack(PACK4096, ids)}
      local av = above_ids and above_ids:find(pat, 1, true) and {string.unpack(PACK4096, above_ids)} or nil
      local changed = false
      for i = 1, 4096 do
        if v[i] == water then
          local up
          if i <= 3840 then up = v[i + 256] else up = av and av[i - 3840] end
          if up == water then
            v[i] = 0
            changed = true
            emptied = emptied + 1
          end
        end
      end
      if changed then v[4097] = nil out[key] = string.pack(PACK4096, table.unpack(v, 1, 4096)) end
    end
  end
  -- Deep cells were decided from the original data (a cell stays deep even when the one above was emptied).
  for key, ids in pairs(out) do sections[key] = ids end
  return emptied
end

function M.load(opt)
  local t0 = torte.clock()
  opt.registry = opt.registry or blocks.registry()
  local files = opt.files or M.region_files(assert(opt.dir, "minecraft.world.load: 'dir' or 'files' is required"))
  if #files == 0 then error(("minecraft.world.load: no region files (r.X.Z.mca) in '%s' or its region/ folder"):format(
    opt.dir), 0) end
  local stats = {files = #files, chunks = 0, full = 0, not_full = 0, bad = 0, bad_messages = {}, sections = 0,
                 non_air = 0, data_versions = {}, statuses = {}, formats = {}, probes = {}, emitters = {},
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
        if not opt.skip_bad_chunks then error(region.bare_error(err), 0) end
        stats.bad = stats.bad + 1
        stats.bad_messages[#stats.bad_messages + 1] = region.bare_error(err)
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
