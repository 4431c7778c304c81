-- minecraft.region: Anvil region files (r.<X>.<Z>.mca) read with torte.data's generic building blocks.
--
--   local region = require "minecraft.region"
--   local r = region.open("world/region/r.0.-1.mca")   -- whole file read once; r.rx, r.rz from the name
--   for _, c in ipairs(r:chunks()) do                   -- the chunks present: {x, z (world chunk coordinates),
--     local root = r:read(c)                            --   lx, lz (0..31 in the region), sector, sectors, time}
--   end
--
-- A file is an 8 KiB header (1024 big-endian locations: 3 bytes sector offset, 1 byte sector count; then 1024
-- timestamps) followed by chunks in 4 KiB sectors. A chunk is a 4-byte big-endian length, a compression byte
-- (1 gzip, 2 zlib, 3 uncompressed, 4 LZ4, 127 custom; +128: the data is in the file c.<x>.<z>.mcc beside the
-- region) and the NBT payload. Every error names the file and the chunk.
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

-- Region coordinates from a file name "r.X.Z.mca" (nil if the name does not match).
function M.coords(path)
  local x, z = path:match("r%.(%-?%d+)%.(%-?%d+)%.mca$")
  if not x then return nil end
  return math.tointeger(tonumber(x)), math.tointeger(tonumber(z))
end

function M.open(path)
  local rx, rz = M.coords(path)
  if not rx then error(("%s: not a region file name (expected r.<X>.<Z>.mca)"):format(path), 0) end
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

function Region:where(c)
  return ("%s: chunk (%d, %d) (entry %d,%d of the region)"):format(self.path, c.x, c.z, c.lx, c.lz)
end

-- The chunk's NBT root compound (a table). Errors name the file and chunk.
function Region:read(c)
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
    fail("LZ4 compression (type 4) is not supported")
  else
    fail(("unknown compression type %d"):format(compression))
  end
  local ok, root = pcall(data.nbt, raw)
  if not ok then fail(bare(root)) end
  if type(root) ~= "table" then fail("the NBT root is not a compound") end
  return root
end

return M
