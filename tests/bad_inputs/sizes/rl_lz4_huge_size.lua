-- An LZ4 block of 4 bytes said to decompress to 2 GB: refused before the output is allocated.
-- expect: torte.data.lz4_block: corrupt input: 4 bytes cannot decode to 2147483647 bytes
local s = torte.data.lz4_block("\x1fabc", 0x7fffffff)
