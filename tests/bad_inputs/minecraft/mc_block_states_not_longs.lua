-- BlockStates stored as an int array instead of a long array.
-- expect: the block data is a list, not a long array
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local states = W.ints({1, 2, 3})
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(4, {"minecraft:stone", "minecraft:dirt"}, states)})}})
require("minecraft.world").load{dir = "."}
