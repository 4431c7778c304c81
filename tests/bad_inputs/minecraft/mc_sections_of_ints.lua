-- Level.Sections is a list of ints.
-- expect: section 1 is a number, not a compound
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.int(1), W.int(2)})}})
require("minecraft.world").load{dir = "."}
