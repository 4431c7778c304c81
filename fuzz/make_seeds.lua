-- Makes the seed corpora of fuzz/corpus/ from the real data in ../shared/data (fuzz/README.md says which seed
-- comes from where). Run from the repository root:
--   build/torte fuzz/make_seeds.lua data=../shared/data out=fuzz/corpus
-- The image seeds are made by fuzz/make-seeds.sh with oiiotool; the kwargs and lua_api seeds are byte
-- programs, minimised from fuzzing runs (make-seeds.sh does not touch them).
-- Every seed stays small (a few KB): meshes are cut to their first vertices and the faces among them, Minecraft
-- chunks to their largest section, without light data.
local opt = torte.options{data = "../shared/data", out = "fuzz/corpus"}
local data = torte.data
local region = require "minecraft.region"

local function write(harness, name, bytes)
  os.execute(("mkdir -p '%s/%s'"):format(opt.out, harness))
  local path = ("%s/%s/%s"):format(opt.out, harness, name)
  local f = assert(io.open(path, "wb"))
  f:write(bytes)
  f:close()
  print(("%-60s %6d bytes"):format(path, #bytes))
end

local function read(path) return data.read_file(opt.data .. "/" .. path) end

-- ---- PLY: the first vertices of a real scan and the faces among them -----------------------------------------
local TYPE_SIZE = {char = 1, uchar = 1, int8 = 1, uint8 = 1, short = 2, ushort = 2, int16 = 2, uint16 = 2,
                   int = 4, uint = 4, int32 = 4, uint32 = 4, float = 4, float32 = 4, double = 8, float64 = 8}
local function ply_header(s)
  local stop = assert(s:find("end_header\r?\n"))
  local header = s:sub(1, stop - 1)
  local body_at = s:find("\n", stop) + 1
  local elements, format = {}, header:match("format (%S+)")
  for line in header:gmatch("[^\n]+") do
    local name, count = line:match("^element (%S+) (%d+)")
    if name then elements[#elements + 1] = {name = name, count = tonumber(count), props = {}} end
    local list_count, list_item, pname = line:match("^property list (%S+) (%S+) (%S+)")
    local ptype, pname2 = line:match("^property (%S+) (%S+)$")
    if list_count then table.insert(elements[#elements].props, {list = true, count = list_count, item = list_item})
    elseif ptype and ptype ~= "list" then table.insert(elements[#elements].props, {type = ptype, name = pname2}) end
  end
  return header, format, elements, body_at
end

-- Keeps the first `nv` vertices and the faces whose indices all fall below nv; writes `out_format`.
local function cut_ply(s, nv, out_format)
  local header, format, elements, at = ply_header(s)
  assert(elements[1].name == "vertex" and elements[2].name == "face")
  local endian = format == "binary_big_endian" and ">" or "<"
  local vprops = elements[1].props
  local verts, faces = {}, {}
  if format == "ascii" then
    local lines = {}
    for line in s:sub(at):gmatch("[^\n]+") do lines[#lines + 1] = line end
    for i = 1, nv do
      local v = {}
      for x in lines[i]:gmatch("%S+") do v[#v + 1] = tonumber(x) end
      verts[i] = v
    end
    for i = elements[1].count + 1, elements[1].count + elements[2].count do
      local f = {}
      for x in lines[i]:gmatch("%S+") do f[#f + 1] = tonumber(x) end
      local ok = true
      for k = 2, #f do if f[k] >= nv then ok = false end end
      if ok then faces[#faces + 1] = {table.unpack(f, 2)} end
    end
  else
    local fmt = endian
    for _, p in ipairs(vprops) do fmt = fmt .. (TYPE_SIZE[p.type] == 8 and "d" or "f") end
    local vsize = string.packsize(fmt)
    for i = 1, nv do verts[i] = {string.unpack(fmt, s, at + (i - 1) * vsize)} ; verts[i][#verts[i]] = nil end
    local p = at + elements[1].count * vsize
    for _ = 1, elements[2].count do
      local n = string.unpack("B", s, p)
      local f = {string.unpack(endian .. ("i4"):rep(n), s, p + 1)}
      f[#f] = nil
      p = p + 1 + 4 * n
      local ok = true
      for k = 1, n do if f[k] >= nv then ok = false end end
      if ok then faces[#faces + 1] = f end
    end
  end
  -- Re-emit the header with the new counts and format.
  local out = header:gsub("format %S+", "format " .. out_format)
  out = out:gsub("element vertex %d+", "element vertex " .. nv):gsub("element face %d+", "element face " .. #faces)
  out = out .. "end_header\n"
  local body = {}
  if out_format == "ascii" then
    for _, v in ipairs(verts) do
      local t = {}
      for k, x in ipairs(v) do t[k] = ("%.7g"):format(x) end
      body[#body + 1] = table.concat(t, " ") .. "\n"
    end
    for _, f in ipairs(faces) do body[#body + 1] = #f .. " " .. table.concat(f, " ") .. "\n" end
  else
    local e = out_format == "binary_big_endian" and ">" or "<"
    for _, v in ipairs(verts) do
      for k, x in ipairs(v) do body[#body + 1] = string.pack(e .. (TYPE_SIZE[vprops[k].type] == 8 and "d" or "f"), x) end
    end
    for _, f in ipairs(faces) do body[#body + 1] = string.pack(e .. "B" .. ("i4"):rep(#f), #f, table.unpack(f)) end
  end
  return out .. table.concat(body)
end

write("ply", "bunny-res4-ascii-confidence.ply", cut_ply(read("meshes/bunny/bun_zipper_res4.ply"), 40, "ascii"))
write("ply", "bunny-le.ply", cut_ply(read("bunny.ply"), 60, "binary_little_endian"))
write("ply", "bunny-be.ply", cut_ply(read("bunny.ply"), 60, "binary_big_endian"))
write("ply", "dragon-le-normals.ply", cut_ply(read("meshes/dragon/dragon_100k_binary_le.ply"), 50, "binary_little_endian"))
write("ply", "dragon-ascii-normals.ply", cut_ply(read("meshes/dragon/dragon_100k_binary_le.ply"), 30, "ascii"))
write("ply", "buddha-ascii.ply", cut_ply(read("meshes/happy-buddha/happy_vrip_res3.ply"), 40, "ascii"))
-- What the real files do not show: uvs under each accepted name, quads, other scalar types, a list on vertices,
-- extra elements, CRLF line ends.
write("ply", "uv-quad-types.ply", table.concat({
  "ply", "format ascii 1.0", "comment made by fuzz/make_seeds.lua", "obj_info no object",
  "element vertex 4", "property double x", "property float32 y", "property int16 z", "property uchar red",
  "property float s", "property float t", "property list uchar float extra",
  "element face 2", "property list uint8 uint32 vertex_index", "property int flags",
  "element material 1", "property float shininess", "end_header",
  "0 0 0 255 0 0 2 1.5 2.5", "1 0 0 0 1 0 0", "1 1 0 0 1 1 1 7", "0 1 0 0 0 1 0",
  "4 0 1 2 3 9", "3 0 2 3 -1", "0.5", ""}, "\n"))
write("ply", "texture-uv-le.ply",
  "ply\r\nformat binary_little_endian 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\n" ..
  "property float z\r\nproperty float nx\r\nproperty float ny\r\nproperty float nz\r\nproperty float texture_u\r\n" ..
  "property float texture_v\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n" ..
  string.pack("<ffffffff", 0, 0, 0, 0, 0, 1, 0, 0) .. string.pack("<ffffffff", 1, 0, 0, 0, 0, 1, 1, 0) ..
  string.pack("<ffffffff", 0, 1, 0, 0, 0, 1, 0, 1) .. string.pack("<Bi4i4i4", 3, 0, 1, 2))

-- ---- OBJ / MTL -------------------------------------------------------------------------------------------------
-- The first n of each statement kind, and the faces whose corners all refer to kept elements.
local function cut_obj(text, n)
  local counts, out = {v = 0, vt = 0, vn = 0}, {}
  for line in text:gmatch("[^\n]*") do
    local key = line:match("^%s*(%S+)")
    if counts[key] then
      counts[key] = counts[key] + 1
      if counts[key] <= n then out[#out + 1] = line end
    elseif key == "f" then
      local ok = true
      for corner in line:gmatch("%S+", 2) do
        for idx in corner:gmatch("%-?%d+") do if tonumber(idx) > n then ok = false end end
      end
      if ok then out[#out + 1] = line end
    elseif key ~= nil then
      out[#out + 1] = line
    end
  end
  return table.concat(out, "\n") .. "\n"
end

write("obj", "cornell-box.obj", read("meshes/cornell-box/cornell_box.obj"):gsub("mtllib %S+", "mtllib fuzz.mtl") ..
  "\n#mtl\n" .. read("meshes/cornell-box/cornell_box.mtl"))
write("obj", "spot-v-vt.obj", cut_obj(read("meshes/spot/spot_triangulated.obj"), 60))
local lucy = read("meshes/lucy/lucy_100k.obj")
write("obj", "lucy.obj", cut_obj(lucy:sub(1, 200000), 40))
write("obj", "statements.obj", table.concat({
  "# every statement the reader knows, and some it ignores", "mtllib fuzz.mtl", "o thing", "g part one",
  "v 0 0 0", "v 1 0 0 0.5 0.5 0.5", "v 1 1 0", "v 0 1 0 1", "vt 0 0", "vt 1 0 0", "vt 1 1", "vt 0 1",
  "vn 0 0 1", "vn 0 0 -1", "usemtl lit", "s 1", "f 1/1/1 2/2/1 3/3/1 4/4/1", "f -4//-2 -3//-2 -2//-2",
  "g", "usemtl unknown", "f 1/1 3/3 4/4", "l 1 2", "p 3", "s off", "curv 0 1 1 2", "f 1 2 3",
  "#mtl", "newmtl lit", "Kd 0.5 0.25 0.125", "Ke 4", "map_Kd -s 1 1 1 -clamp on tex.png", "Ns 10",
  "newmtl second", "Kd 1", ""}, "\n"))

-- ---- NBT and Minecraft chunks ----------------------------------------------------------------------------------
-- Copies an NBT value of type `t` at byte `p` of `s`, keeping only the `keep` largest elements of the lists
-- named in PRUNE (sections, entities). Returns the copy and the position after the value.
local PRUNE = {sections = 1, Sections = 1, Entities = 0, TileEntities = 1, block_entities = 1, entities = 0,
               TileTicks = 0, block_ticks = 0, fluid_ticks = 0, LiquidTicks = 0, PostProcessing = 0,
               structures = 0, Structures = 0, Lights = 0, ToBeTicked = 0, LiquidsToBeTicked = 0,
               CarvingMasks = 0}
local DROP = {SkyLight = true, BlockLight = true, CarvingMasks = true, Heightmaps = true, HeightMap = true}
local copy_value
local function copy_name(s, p)
  local n = string.unpack(">I2", s, p)
  return s:sub(p + 2, p + 1 + n), p + 2 + n
end
function copy_value(s, t, p, name)
  if t == 1 then return s:sub(p, p), p + 1
  elseif t == 2 then return s:sub(p, p + 1), p + 2
  elseif t == 3 or t == 5 then return s:sub(p, p + 3), p + 4
  elseif t == 4 or t == 6 then return s:sub(p, p + 7), p + 8
  elseif t == 7 then local n = string.unpack(">i4", s, p); return s:sub(p, p + 3 + n), p + 4 + n
  elseif t == 8 then local n = string.unpack(">I2", s, p); return s:sub(p, p + 1 + n), p + 2 + n
  elseif t == 11 then local n = string.unpack(">i4", s, p); return s:sub(p, p + 3 + 4 * n), p + 4 + 4 * n
  elseif t == 12 then local n = string.unpack(">i4", s, p); return s:sub(p, p + 3 + 8 * n), p + 4 + 8 * n
  elseif t == 9 then
    local et, n = string.unpack(">Bi4", s, p)
    p = p + 5
    local items = {}
    for i = 1, n do items[i], p = copy_value(s, et, p) end
    local keep = PRUNE[name]
    if keep and #items > keep then
      local order = {}
      for i = 1, #items do order[i] = i end
      table.sort(order, function(a, b) return #items[a] > #items[b] or (#items[a] == #items[b] and a < b) end)
      local chosen = {}
      for i = 1, keep do chosen[i] = order[i] end
      table.sort(chosen)
      local kept = {}
      for i, k in ipairs(chosen) do kept[i] = items[k] end
      items = kept
    end
    return string.pack(">Bi4", et, #items) .. table.concat(items), p
  elseif t == 10 then
    local out = {}
    while true do
      local tt = string.unpack("B", s, p)
      p = p + 1
      if tt == 0 then break end
      local n, v
      n, p = copy_name(s, p)
      v, p = copy_value(s, tt, p, n)
      if not DROP[n] and (PRUNE[n] ~= 0 or tt ~= 9) then out[#out + 1] = string.pack(">BI2", tt, #n) .. n .. v end
    end
    return table.concat(out) .. "\0", p
  end
  error("bad tag " .. t)
end
local function prune_nbt(s)
  local t = string.unpack("B", s, 1)
  local n, p = copy_name(s, 2)
  local v = copy_value(s, t, p, n)
  return string.pack(">BI2", t, #n) .. n .. v
end

-- Stored (uncompressed) deflate blocks in a zlib or gzip wrapper: valid streams the fuzzer can edit in place.
local function adler32(s)
  local a, b = 1, 0
  for i = 1, #s do a = (a + s:byte(i)) % 65521; b = (b + a) % 65521 end
  return (b << 16) | a
end
local CRC = {}
for i = 0, 255 do
  local c = i
  for _ = 1, 8 do c = (c & 1 ~= 0) and (0xEDB88320 ~ (c >> 1)) or (c >> 1) end
  CRC[i] = c
end
local function crc32(s)
  local c = 0xFFFFFFFF
  for i = 1, #s do c = CRC[(c ~ s:byte(i)) & 255] ~ (c >> 8) end
  return c ~ 0xFFFFFFFF
end
local function stored_deflate(s)
  local out, i = {}, 1
  repeat
    local part = s:sub(i, i + 65534)
    i = i + #part
    out[#out + 1] = string.pack("<BI2I2", i > #s and 1 or 0, #part, (~#part) & 0xFFFF) .. part
  until i > #s
  return table.concat(out)
end
local function zlib_stored(s) return "\x78\x01" .. stored_deflate(s) .. string.pack(">I4", adler32(s)) end
local function gzip_stored(s)
  return "\x1f\x8b\x08\0\0\0\0\0\0\xff" .. stored_deflate(s) .. string.pack("<I4I4", crc32(s), #s & 0xFFFFFFFF)
end

-- One chunk from each world format: the smallest pruned NBT of at least 1500 bytes among chunks with blocks.
local WORLDS = {
  {"prismarine-1.8.9/r.-1.0.mca", "legacy-1.8"}, {"prismarine-1.12.2/r.0.-1.mca", "legacy-1.12"},
  {"mcaselector-anvil113/r.0.0.mca", "palette-1.13"}, {"prismarine-1.14.4/r.0.-1.mca", "palette-1.14"},
  {"prismarine-1.16/r.0.-1.mca", "palette-1.16"}, {"querz-nbt-1.18.2/r.0.0.mca", "root-1.18"},
  {"bluenbt-1.20.1-paper/r.0.0.mca", "root-1.20"}, {"prismarine-1.21.1/r.0.0.mca", "root-1.21"},
}
local chunks = {}
for _, w in ipairs(WORLDS) do
  local r = region.open(opt.data .. "/minecraft/" .. w[1])
  local best
  for i, c in ipairs(r:chunks()) do
    if i > 64 then break end
    local ok, raw = pcall(r.payload, r, c)
    if ok then
      local pruned = prune_nbt(raw)
      if #pruned >= 1500 and (not best or #pruned < #best.nbt) then
        -- prefer chunks whose sections hold blocks
        if pruned:find("Palette", 1, true) or pruned:find("palette", 1, true) or pruned:find("Blocks", 1, true) then
          best = {nbt = pruned, c = c, compressed = r.bytes:sub(c.sector * 4096 + 6, c.sector * 4096 + 4 +
                  string.unpack(">I4", r.bytes, c.sector * 4096 + 1))}
        end
      end
    end
  end
  assert(best, "no chunk with blocks in " .. w[1])
  chunks[#chunks + 1] = {name = w[2], nbt = best.nbt, compressed = best.compressed}
end

for _, c in ipairs(chunks) do
  assert(data.nbt(c.nbt))  -- the pruned NBT still parses
  -- nbt: offset 0, 4-bit fields, count 4096 / 17 * 17, spanning
  write("nbt", c.name .. ".nbt", string.char(0, 4, 240, 0) .. c.nbt)
end
local level = data.gunzip(read("minecraft/bluenbt-1.20.1-paper/level.dat"))
write("nbt", "level-dat-1.20.nbt", string.char(0, 5, 30, 1) .. prune_nbt(level))
-- two roots in one string, as nbt(s, next_offset) reads them
write("nbt", "two-roots.nbt", string.char(0, 1, 8, 0) ..
  "\10\0\1a\1\0\1b\5\8\0\1s\0\3abc\0" .. "\9\0\1l\3\0\0\0\2\0\0\0\1\0\0\0\2")

-- inflate: mode byte (0 inflate, 1 gunzip, 2 lz4_block + 2-byte size, 3 LZ4Block stream), then the stream.
local small = chunks[1]
table.sort(chunks, function(a, b) return #a.compressed < #b.compressed end)
write("inflate", "real-zlib-chunk.bin", "\0" .. chunks[1].compressed)
write("inflate", "stored-zlib.bin", "\0" .. zlib_stored(small.nbt:sub(1, 1500)))
write("inflate", "real-gzip-level-dat.bin", "\1" .. read("minecraft/bluenbt-1.20.1-paper/level.dat"))
write("inflate", "stored-gzip.bin", "\1" .. gzip_stored(small.nbt:sub(1, 1500)))
local piece = level:sub(1, 1500)
write("inflate", "lz4-block.bin", "\2" .. string.pack("<I2", #piece) .. data.lz4_compress(piece))
write("inflate", "lz4-stream.bin", "\3" .. region.lz4_stream_encode(piece, 1024))

-- region: options byte, header entry count, location words, then the file from sector 2 on (see fuzz_region.cc).
local function region_seed(options, chunk_list)
  local words, sectors, next_sector = {}, {}, 2
  for i, ch in ipairs(chunk_list) do
    local body = string.pack(">I4B", #ch.payload + 1, ch.compression) .. ch.payload
    local n = (#body + 4095) // 4096
    words[#words + 1] = string.pack(">I4", (next_sector << 8) | n)
    -- the last sector is not padded: shorter seeds, and the reader must cope with a file ending mid-sector
    sectors[#sectors + 1] = i == #chunk_list and body or body .. ("\0"):rep(n * 4096 - #body)
    next_sector = next_sector + n
  end
  local file = table.concat(sectors)
  return string.char(options, #chunk_list) .. table.concat(words) .. file
end
for i, c in ipairs(chunks) do
  write("region", c.name .. "-raw.bin", region_seed(i % 16, {{payload = c.nbt, compression = 3}}))
end
write("region", "zlib-stored.bin", region_seed(2, {{payload = zlib_stored(small.nbt), compression = 2}}))
write("region", "gzip-stored.bin", region_seed(4, {{payload = gzip_stored(small.nbt), compression = 1}}))
write("region", "lz4.bin", region_seed(6, {{payload = region.lz4_stream_encode(small.nbt, 4096), compression = 4}}))
write("region", "real-zlib.bin", region_seed(1, {{payload = chunks[1].compressed, compression = 2}}))
write("region", "two-chunks.bin", region_seed(0, {{payload = chunks[2].nbt, compression = 3},
                                                   {payload = chunks[3].nbt, compression = 3}}))
write("region", "external.bin", region_seed(1, {{payload = "", compression = 130}}))
