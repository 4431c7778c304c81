-- A header entry pointing into the header itself (sector 1).
-- expect: bad sector offset 1 (inside the header)
-- where: r\.0\.0\.mca: chunk \(3, 5\) \(entry 3,5 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{3, 5, W.chunk(3, 5), location = (1 << 8) | 1}})
require("minecraft.world").load{dir = "."}
