-- A palette entry whose Properties is an int.
-- expect: palette entry 1 (minecraft:oak_slab): Properties is a number, not a compound
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local slab = W.compound{{"Name", W.string("minecraft:oak_slab")}, {"Properties", W.int(7)}}
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(4, {slab})})}})
require("minecraft.world").load{dir = "."}
