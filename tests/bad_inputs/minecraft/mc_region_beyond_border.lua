-- A region file named beyond Minecraft's world border.
-- expect: region (60000, 0) lies beyond Minecraft's world border
-- where: r\.60000\.0\.mca: region
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.60000.0.mca", {{0, 0, W.chunk(1920000, 0)}})
require("minecraft.world").load{dir = "."}
