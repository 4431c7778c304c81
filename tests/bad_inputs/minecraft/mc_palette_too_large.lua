-- A palette of 5000 entries: more than a section has blocks.
-- expect: the palette has 5000 entries (a section holds 4096 blocks)
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local names = {}
for i = 1, 5000 do names[i] = "minecraft:block_" .. i end
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(4, names, W.longs(4096))})}})
require("minecraft.world").load{dir = "."}
