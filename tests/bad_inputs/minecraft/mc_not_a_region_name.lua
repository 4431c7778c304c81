-- An explicit file list naming a file that is not r.X.Z.mca.
-- expect: not a region file name (expected r.<X>.<Z>.mca)
-- where: region\.dat: not a region
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("region.dat", {{0, 0, W.chunk(0, 0)}})
require("minecraft.world").load{files = {"region.dat"}}
