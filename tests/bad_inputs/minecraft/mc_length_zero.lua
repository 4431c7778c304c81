-- A chunk whose length field is 0.
-- expect: chunk length is 0
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0), length = 0}})
require("minecraft.world").load{dir = "."}
