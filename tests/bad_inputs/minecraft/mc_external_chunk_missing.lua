-- A chunk stored outside the region (type 128 + 2) whose c.0.0.mcc file is missing.
-- expect: the chunk is stored in an external file: 
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, "", compression = 130}})
require("minecraft.world").load{dir = "."}
