-- A section whose Y (an int here, a byte in every real format) is 100000.
-- expect: section 1 has Y=100000, outside -128..127
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(nil, {"minecraft:stone"}, nil, {{"Y", W.int(100000)}})})}})
require("minecraft.world").load{dir = "."}
