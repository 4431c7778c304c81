-- A section without its Y.
-- expect: section 1 has no Y
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(nil, {"minecraft:stone"})})}})
require("minecraft.world").load{dir = "."}
