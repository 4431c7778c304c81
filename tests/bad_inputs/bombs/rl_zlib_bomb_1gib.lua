-- A 6.8 MB zlib stream of 1 GiB of zeros: stops at the 256 MB default output limit (it took 3.2 GB).
-- expect: torte.data.inflate: the stream decompresses to more than 256 MB (the output limit; pass a larger one as the second argument)
-- Raw deflate of zeros without a compressor: one fixed-Huffman block holding a literal 0, then copies of 258
-- bytes at distance 1 (13 bits each; 8 of them are the same 13 bytes), 159 output bytes per input byte.
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local deflate_zeros = case.deflate_zeros
local z = "\x78\x01" .. deflate_zeros(520000)
local s = torte.data.inflate(z)
