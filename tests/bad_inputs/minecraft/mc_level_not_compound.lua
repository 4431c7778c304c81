-- The chunk's Level is an int.
-- expect: Level is a number, not a compound
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.nbt(W.compound{{"DataVersion", W.int(2566)}, {"Level", W.int(1)}})}})
require("minecraft.world").load{dir = "."}
