-- A header entry pointing at sector 50 of a file of 3 sectors.
-- expect: starts at byte 204800 but the file has only 12288 bytes
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0), location = (50 << 8) | 1}})
require("minecraft.world").load{dir = "."}
