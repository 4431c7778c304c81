-- A chunk whose NBT root is a string.
-- expect: the NBT root is not a compound
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.nbt(W.string("chunk"))}})
require("minecraft.world").load{dir = "."}
