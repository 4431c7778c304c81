-- A chunk whose length field says 1 MB in a file of 3 sectors.
-- expect: needs 1000000 bytes but the file ends after
-- where: r\.-1\.2\.mca: chunk \(-1, 64\) \(entry 31,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.-1.2.mca", {{31, 0, W.chunk(-1, 64), length = 1000000}})
require("minecraft.world").load{dir = "."}
