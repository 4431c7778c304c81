-- A gzip stream cut before its end (a torte-made stream of zeros).
-- expect: torte.data.gunzip: truncated input: the compressed stream ends early
-- Raw deflate of zeros without a compressor: one fixed-Huffman block holding a literal 0, then copies of 258
-- bytes at distance 1 (13 bits each; 8 of them are the same 13 bytes), 159 output bytes per input byte.
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local deflate_zeros = case.deflate_zeros
local g = "\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03" .. deflate_zeros(100)
local s = torte.data.gunzip(g:sub(1, -10))
