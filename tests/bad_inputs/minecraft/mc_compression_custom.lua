-- Compression type 127 (1.20.5+ custom algorithms), which torte does not read.
-- expect: custom compression (type 127
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, string.pack(">s2", "zstd") .. W.chunk(0, 0), compression = 127}})
require("minecraft.world").load{dir = "."}
