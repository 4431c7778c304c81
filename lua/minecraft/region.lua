-- minecraft.region: Anvil region files (r.<X>.<Z>.mca) read with torte.data's generic building blocks.
--
--   local region = require "minecraft.region"
--   local r = region.open("world/region/r.0.-1.mca")   -- whole file read once; r.rx, r.rz from the name
--   for _, c in ipairs(r:chunks()) do                   -- the chunks present: {x, z (world chunk coordinates),
--     local root = r:read(c)                            --   lx, lz (0..31 in the region), sector, sectors, time}
--     local bytes = r:payload(c)                        -- or the decompressed NBT bytes
--   end
--
-- A file is an 8 KiB header (1024 big-endian locations: 3 bytes sector offset, 1 byte sector count; then 1024
-- timestamps) followed by chunks in 4 KiB sectors. A chunk is a 4-byte big-endian length, a compression byte
-- (1 gzip, 2 zlib, 3 uncompressed, 4 LZ4, 127 custom; +128: the data is in the file c.<x>.<z>.mcc beside the
-- region) and the NBT payload. Every error names the file and the chunk. LZ4 (1.20.5+): see M.lz4_stream; what
-- one chunk may decompress to is bounded by M.MAX_CHUNK_BYTES.
local torte = require "torte"
local data = torte.data

local M = {}

local Region = {}
Region.__index = Region

-- Strips the "[torte] minecraft.x:12: " / "file.lua:3: " location a nested error carries.
local function bare(err)
  err = tostring(err)
  return (err:gsub("^%[torte%] [%w._]+:%d+: ", ""):gsub("^[^:%s]+%.lua:%d+: ", ""))
end
M.bare_error = bare

-- An error met while loading a chunk as the one line a user sees: "<file>: chunk (x, z) (...): <what>". The
-- loader's own messages start so already; anything else (a binding's error, a Lua error of the decoder such as
-- indexing a value of a type no check expected, an error of the caller's sink) gets the prefix, and a Lua error
-- raised inside these modules keeps its module line at the end for a bug report.
function M.chunk_error(err, where)
  err = tostring(err)
  if err:sub(1, #where) == where then return err end
  local module, line, what = err:match("^%[torte%] ([%w._]+):(%d+): (.*)$")
  if module then
    if what:find("^torte%.") then return where .. ": " .. what end  -- a binding's error says which binding
    return ("%s: %s (in %s:%s)"):format(where, what, module, line)
  end
  return where .. ": " .. err
end

-- Region coordinates from a file name "r.X.Z.mca" (nil if the name does not match).
function M.coords(path)
  local x, z = path:match("r%.(%-?%d+)%.(%-?%d+)%.mca$")
  if not x then return nil end
  return math.tointeger(tonumber(x)), math.tointeger(tonumber(z))
end

-- Minecraft's world border is 30 million blocks from the origin: 58594 regions.
M.MAX_REGION = 58594
-- The most a chunk may decompress to: real chunks take well under a few MB, so this only stops bombs.
M.MAX_CHUNK_BYTES = 256 * 1024 * 1024

function M.open(path)
  if type(path) ~= "string" then error("minecraft.region.open expects a file name, got " .. type(path), 2) end
  local rx, rz = M.coords(path)
  if not rx then error(("%s: not a region file name (expected r.<X>.<Z>.mca)"):format(path), 0) end
  if math.abs(rx) > M.MAX_REGION or math.abs(rz) > M.MAX_REGION then
    error(("%s: region (%d, %d) lies beyond Minecraft's world border (|X|, |Z| <= %d)"):format(path, rx, rz,
                                                                                             M.MAX_REGION), 0)
  end
  local ok, bytes = pcall(data.read_file, path)
  if not ok then error(bare(bytes), 0) end
  if #bytes ~= 0 and #bytes < 8192 then
    error(("%s: truncated region file: %d bytes, the header alone is 8192"):format(path, #bytes), 0)
  end
  return setmetatable({path = path, bytes = bytes, rx = rx, rz = rz,
                       dir = path:match("^(.*)[/\\]") or "."}, Region)
end

-- The chunks present in the file, in file-header order.
function Region:chunks()
  local out, s = {}, self.bytes
  if #s == 0 then return out end
  for i = 0, 1023 do
    local loc = string.unpack(">I4", s, 4 * i + 1)
    if loc ~= 0 then
      local lx, lz = i % 32, i // 32
      out[#out + 1] = {
        index = i, lx = lx, lz = lz, x = self.rx * 32 + lx, z = self.rz * 32 + lz,
        sector = loc >> 8, sectors = loc & 255, time = string.unpack(">I4", s, 4096 + 4 * i + 1),
      }
    end
  end
  return out
end

-- LZ4 chunks (compression 4, Minecraft 1.20.5+) are written by lz4-java's LZ4BlockOutputStream: blocks of
--   "LZ4Block" (8 bytes), token (1: method 0x10 raw / 0x20 LZ4, low nibble L: blocks hold at most 2^(10+L) bytes),
--   compressed length, decompressed length, checksum (3 x int32 little-endian), then the compressed bytes,
-- and an end block with both lengths and the checksum 0. The checksum is XXH32 (seed 0x9747b28c) of the
-- decompressed bytes, masked to 28 bits (lz4-java's StreamingXXHash32.asChecksum). Returns the decompressed
-- bytes; errors say which block and byte and what is wrong.
local LZ4_MAGIC = "LZ4Block"
local LZ4_SEED = 0x9747b28c
function M.lz4_stream(s, max_bytes)
  max_bytes = max_bytes or M.MAX_CHUNK_BYTES
  local out, pos, n, block, total = {}, 1, #s, 0, 0
  while true do
    block = block + 1
    local at = ("LZ4 block %d at byte %d"):format(block, pos - 1)
    if pos > n then error(at .. ": truncated input: the stream ends without its end block", 0) end
    if n - pos + 1 < 21 then
      error(("%s: truncated input: a block header needs 21 bytes, %d left"):format(at, n - pos + 1), 0)
    end
    if s:sub(pos, pos + 7) ~= LZ4_MAGIC then error(at .. ": bad magic (expected 'LZ4Block')", 0) end
    local token, clen, dlen, check = string.unpack("<Bi4i4I4", s, pos + 8)
    local method, level = token & 0xF0, token & 0x0F
    if method ~= 0x10 and method ~= 0x20 then
      error(("%s: unknown compression method 0x%02x"):format(at, method), 0)
    end
    if clen < 0 or dlen < 0 or dlen > (1 << (10 + level)) or (dlen == 0 and clen ~= 0) or (dlen ~= 0 and clen == 0)
       or (method == 0x10 and clen ~= dlen) then
      error(("%s: bad lengths (%d compressed, %d decompressed, block size %d)"):format(at, clen, dlen,
                                                                                       1 << (10 + level)), 0)
    end
    pos = pos + 21
    total = total + dlen
    if total > max_bytes then
      error(("%s: the stream decompresses to more than %d bytes (the limit for one chunk)"):format(at, max_bytes), 0)
    end
    if dlen == 0 then  -- the end block
      if check ~= 0 then error(at .. ": corrupt end block (non-zero checksum)", 0) end
      if pos <= n then error(("%s: %d bytes of trailing data after the end block"):format(at, n - pos + 1), 0) end
      break
    end
    if n - pos + 1 < clen then
      error(("%s: truncated input: %d compressed bytes, %d left"):format(at, clen, n - pos + 1), 0)
    end
    local raw
    if method == 0x10 then
      raw = s:sub(pos, pos + clen - 1)
    else
      local ok, r = pcall(data.lz4_block, s, dlen, pos, pos + clen - 1)
      if not ok then error(at .. ": " .. bare(r), 0) end
      raw = r
    end
    if (data.xxhash32(raw, LZ4_SEED) & 0x0FFFFFFF) ~= (check & 0x0FFFFFFF) then
      error(at .. ": checksum mismatch (corrupt data)", 0)
    end
    out[#out + 1] = raw
    pos = pos + clen
  end
  return table.concat(out)
end

-- The inverse of M.lz4_stream (as LZ4BlockOutputStream writes with 64 KiB blocks), for tests and writers.
function M.lz4_stream_encode(s, block_size)
  block_size = block_size or 65536
  local level = 0
  while (1 << (10 + level)) < block_size do level = level + 1 end
  local out = {}
  for i = 1, #s, block_size do
    local chunk = s:sub(i, i + block_size - 1)
    local z = data.lz4_compress(chunk)
    local method = 0x20
    if #z >= #chunk then z, method = chunk, 0x10 end
    local check = data.xxhash32(chunk, LZ4_SEED) & 0x0FFFFFFF
    out[#out + 1] = LZ4_MAGIC .. string.pack("<Bi4i4I4", method | level, #z, #chunk, check) .. z
  end
  out[#out + 1] = LZ4_MAGIC .. string.pack("<Bi4i4I4", 0x10 | level, 0, 0, 0)
  return table.concat(out)
end

function Region:where(c)
  return ("%s: chunk (%d, %d) (entry %d,%d of the region)"):format(self.path, c.x, c.z, c.lx, c.lz)
end

-- The chunk's decompressed NBT bytes. Errors name the file and chunk.
function Region:payload(c)
  local s = self.bytes
  local function fail(msg) error(self:where(c) .. ": " .. msg, 0) end
  local start = c.sector * 4096
  if c.sector < 2 then fail(("bad sector offset %d (inside the header)"):format(c.sector)) end
  if start + 5 > #s then
    fail(("starts at byte %d but the file has only %d bytes (truncated region file?)"):format(start, #s))
  end
  local length, compression = string.unpack(">I4B", s, start + 1)
  if length < 1 then fail("chunk length is 0") end
  local payload
  if compression & 128 ~= 0 then  -- stored outside: c.<x>.<z>.mcc
    local file = ("%s/c.%d.%d.mca"):format(self.dir, c.x, c.z):gsub("mca$", "mcc")
    local ok, ext = pcall(data.read_file, file)
    if not ok then fail("the chunk is stored in an external file: " .. bare(ext)) end
    payload = ext
    compression = compression & 127
  else
    if start + 4 + length > #s then
      fail(("needs %d bytes but the file ends after %d (truncated region file?)"):format(length,
                                                                                        #s - start - 4))
    end
    payload = s:sub(start + 6, start + 4 + length)
  end
  local raw
  if compression == 2 then
    local ok, r = pcall(data.inflate, payload)
    if not ok then fail(bare(r)) end
    raw = r
  elseif compression == 1 then
    local ok, r = pcall(data.gunzip, payload)
    if not ok then fail(bare(r)) end
    raw = r
  elseif compression == 3 then
    raw = payload
  elseif compression == 4 then
    local ok, r = pcall(M.lz4_stream, payload)
    if not ok then fail(bare(r)) end
    raw = r
  elseif compression == 127 then
    fail("custom compression (type 127, Minecraft 1.20.5+ with a named algorithm) is not supported")
  else
    fail(("unknown compression type %d (known: 1 gzip, 2 zlib, 3 none, 4 LZ4)"):format(compression))
  end
  return raw
end

-- The chunk's NBT root compound (a table). Errors name the file and chunk.
function Region:read(c)
  local raw = self:payload(c)
  local function fail(msg) error(self:where(c) .. ": " .. msg, 0) end
  local ok, root = pcall(data.nbt, raw)
  if not ok then fail(bare(root)) end
  if type(root) ~= "table" then fail("the NBT root is not a compound") end
  return root
end

return M
