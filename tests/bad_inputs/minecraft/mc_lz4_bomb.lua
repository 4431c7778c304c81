-- An LZ4 (type 4) chunk that decompresses to more than a chunk may (the limit lowered to 1 MiB here so the case
-- stays cheap; the default is 256 MiB): refused at the block that passes it, before decompressing it.
-- expect: the stream decompresses to more than 1048576 bytes (the limit for one chunk)
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\): LZ4 block 17 at byte
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local region = require "minecraft.region"
region.MAX_CHUNK_BYTES = 1 << 20
W.region("r.0.0.mca", {{0, 0, region.lz4_stream_encode(("\0"):rep(2 << 20)), compression = 4}})
require("minecraft.world").load{dir = "."}
