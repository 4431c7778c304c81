-- A zlib stream of 2 MB of zeros against an explicit 1 MB limit.
-- expect: torte.data.inflate: the stream decompresses to more than 1.0 MB
-- Raw deflate of zeros without a compressor: one fixed-Huffman block holding a literal 0, then copies of 258
-- bytes at distance 1 (13 bits each; 8 of them are the same 13 bytes), 159 output bytes per input byte.
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local deflate_zeros = case.deflate_zeros
local z = "\x78\x01" .. deflate_zeros(1000)
local s = torte.data.inflate(z, 1 << 20)
