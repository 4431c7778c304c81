-- DataVersion is a string.
-- expect: DataVersion is not an integer
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.nbt(W.compound{{"DataVersion", W.string("2566")}, {"Level", W.compound{}}})}})
require("minecraft.world").load{dir = "."}
