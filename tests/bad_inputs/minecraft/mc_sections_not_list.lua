-- Level.Sections is a string.
-- expect: the section list is a string or byte array, not a list
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, nil, {{"Sections", W.string("none")}})}})
require("minecraft.world").load{dir = "."}
