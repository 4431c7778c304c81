-- A region file whose only chunk is a zlib bomb of 1 GiB: the error names the file and the chunk.
-- expect: chunk (0, 0) (entry 0,0 of the region): torte.data.inflate: the stream decompresses to more than 256 MB
-- where: r\.0\.0\.mca: chunk
-- Raw deflate of zeros without a compressor: one fixed-Huffman block holding a literal 0, then copies of 258
-- bytes at distance 1 (13 bits each; 8 of them are the same 13 bytes), 159 output bytes per input byte.
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, deflate_zeros = case.write, case.deflate_zeros
local payload = "\x78\x01" .. deflate_zeros(520000)
local header = string.pack(">I4", (2 << 8) | 255) .. ("\0"):rep(8188)
write("r.0.0.mca", header .. string.pack(">I4B", #payload + 1, 2) .. payload)
local region = require "minecraft.region"
local r = region.open("r.0.0.mca")
for _, c in ipairs(r:chunks()) do r:read(c) end
