-- A zlib-compressed NBT list of 2^31 - 1 empty compounds (each one byte): inflate stops at its limit
-- before the NBT reader builds a table of two billion entries.
-- expect: torte.data.inflate: the stream decompresses to more than 256 MB
-- Raw deflate of zeros without a compressor: one fixed-Huffman block holding a literal 0, then copies of 258
-- bytes at distance 1 (13 bits each; 8 of them are the same 13 bytes), 159 output bytes per input byte.
-- The NBT head, then zeros (TAG_End: empty compounds) from the bomb: a list of compounds, 0x7fffffff long.
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local deflate_zeros = case.deflate_zeros
local head = "\x09\x00\x01L\x0a\x7f\xff\xff\xff"
local z = "\x78\x01" .. deflate_zeros(2080000)
local nbt = torte.data.nbt(head .. torte.data.inflate(z))
