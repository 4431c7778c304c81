-- Block states pointing past the end of a two-entry palette (every 4-bit field is 5).
-- expect: block index 5 is outside the palette of 2
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local states = W.longs(256, 0x5555555555555555)
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(4, {"minecraft:stone", "minecraft:dirt"}, states)})}})
require("minecraft.world").load{dir = "."}
