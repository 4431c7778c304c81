-- A 27 MB gzip stream of 4 GiB of zeros (it took 4 GB).
-- expect: torte.data.gunzip: the stream decompresses to more than 256 MB
-- Raw deflate of zeros without a compressor: one fixed-Huffman block holding a literal 0, then copies of 258
-- bytes at distance 1 (13 bits each; 8 of them are the same 13 bytes), 159 output bytes per input byte.
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local deflate_zeros = case.deflate_zeros
local g = "\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03" .. deflate_zeros(2080000)
local s = torte.data.gunzip(g)
