-- A region file whose only chunk is a zlib bomb of 1 GiB: the error names the file and the chunk.
-- expect: chunk (0, 0) (entry 0,0 of the region): torte.data.inflate: the stream decompresses to more than 256 MB
-- where: r\.0\.0\.mca: chunk
local function write(name, bytes)
  local f = assert(io.open(name, "wb"))
  f:write(bytes)
  f:close()
end
-- Raw deflate of zeros without a compressor: one fixed-Huffman block holding a literal 0, then copies of 258
-- bytes at distance 1 (13 bits each; 8 of them are the same 13 bytes), 159 output bytes per input byte.
local function deflate_zeros(copies8)
  return "\x63\x18\x05" .. ("\xa3\x60\x14\x8c\x82\x51\x30\x0a\x46\xc1\x28\x18\x05"):rep(copies8) .. "\x00"
end
local payload = "\x78\x01" .. deflate_zeros(520000)
local header = string.pack(">I4", (2 << 8) | 255) .. ("\0"):rep(8188)
write("r.0.0.mca", header .. string.pack(">I4B", #payload + 1, 2) .. payload)
local region = require "minecraft.region"
local r = region.open("r.0.0.mca")
for _, c in ipairs(r:chunks()) do r:read(c) end
