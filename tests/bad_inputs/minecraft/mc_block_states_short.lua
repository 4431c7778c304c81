-- BlockStates with 10 longs where 256 are needed.
-- expect: torte.data.unpack_bits: 4096 padded 4-bit fields need 256 longs, got 10
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local states = W.longs(10)
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(4, {"minecraft:stone", "minecraft:dirt"}, states)})}})
require("minecraft.world").load{dir = "."}
