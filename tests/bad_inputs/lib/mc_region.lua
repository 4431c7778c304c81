-- Shared by the minecraft cases of the bad-input catalogue (loaded with dofile(torte.args.lib); not a case
-- itself: the catalogue runs *.lua only). Builds NBT, chunks and Anvil region files at run time, so the
-- catalogue stays text. Chunks are stored uncompressed (compression type 3) unless a case says otherwise.
local P = string.pack
local W = {}

-- Tags are {type id, payload}.
function W.byte(v) return {1, P(">i1", v)} end
function W.int(v) return {3, P(">i4", v)} end
function W.long(v) return {4, P(">i8", v)} end
function W.string(s) return {8, P(">s2", s)} end
function W.bytes(s) return {7, P(">i4", #s) .. s} end
function W.ints(t)
  local out = {P(">i4", #t)}
  for _, v in ipairs(t) do out[#out + 1] = P(">i4", v) end
  return {11, table.concat(out)}
end
-- A long array of n longs, all `v` (default 0).
function W.longs(n, v)
  return {12, P(">i4", n) .. P(">i8", v or 0):rep(n)}
end
-- A list of tags of one type (an empty list has element type 0).
function W.list(items)
  local t = items[1] and items[1][1] or 0
  local out = {P(">Bi4", t, #items)}
  for _, item in ipairs(items) do out[#out + 1] = item[2] end
  return {9, table.concat(out)}
end
-- A compound from an ordered list of {name, tag} (nil tags are left out).
function W.compound(fields)
  local out = {}
  for _, f in ipairs(fields) do
    if f[2] then out[#out + 1] = P("B", f[2][1]) .. P(">s2", f[1]) .. f[2][2] end
  end
  return {10, table.concat(out) .. "\0"}
end
-- The bytes of an NBT file whose root is `tag` (a compound for chunks).
function W.nbt(tag) return P("B", tag[1]) .. P(">s2", "") .. tag[2] end

-- A 1.16 section (padded palette, DataVersion 2566): y, a palette of block names (or of any tags) and its block
-- states (default: 256 longs of zeros: every block is palette entry 0). `extra` fields are appended.
function W.section(y, palette, states, extra)
  local entries = {}
  for i, e in ipairs(palette) do
    entries[i] = type(e) == "string" and W.compound{{"Name", W.string(e)}} or e
  end
  local fields = {{"Y", y and W.byte(y)}, {"Palette", W.list(entries)}, {"BlockStates", states or W.longs(256)}}
  for _, f in ipairs(extra or {}) do fields[#fields + 1] = f end
  return W.compound(fields)
end

-- A 1.16 chunk (DataVersion 2566, Level.Sections) at chunk (x, z) holding `sections` (tags; default one section
-- of stone). `level` fields replace or extend the Level compound's.
function W.chunk(x, z, sections, level)
  local fields = {{"xPos", W.int(x)}, {"zPos", W.int(z)}, {"Status", W.string("full")},
                  {"Sections", W.list(sections or {W.section(4, {"minecraft:stone"})})}}
  for _, f in ipairs(level or {}) do
    local replaced = false
    for _, g in ipairs(fields) do
      if g[1] == f[1] then g[2], replaced = f[2], true end
    end
    if not replaced then fields[#fields + 1] = f end
  end
  return W.nbt(W.compound{{"DataVersion", W.int(2566)}, {"Level", W.compound(fields)}})
end

-- A region file at `path` (r.X.Z.mca): `chunks` are {lx, lz, payload bytes[, compression = 3]}; a chunk's
-- `location` overrides its header entry (sector offset << 8 | sector count) and `length` its length field.
function W.region(path, chunks)
  local loc, body, sector = {}, {}, 2
  for _, c in ipairs(chunks) do
    local bytes = P(">I4B", c.length or #c[3] + 1, c.compression or 3) .. c[3]
    local n = (#bytes + 4095) // 4096
    assert(n < 256, "a chunk of 1 MiB or more does not fit a region header entry")
    body[#body + 1] = bytes .. ("\0"):rep(n * 4096 - #bytes)
    loc[c[1] + 32 * c[2]] = c.location or (sector << 8) | n
    sector = sector + n
  end
  local h = {}
  for i = 0, 1023 do h[#h + 1] = P(">I4", loc[i] or 0) end
  for i = 0, 1023 do h[#h + 1] = P(">I4", 1700000000) end
  W.write(path, table.concat(h) .. table.concat(body))
end

function W.write(path, bytes)
  local f = assert(io.open(path, "wb"))
  f:write(bytes)
  f:close()
end

return W
