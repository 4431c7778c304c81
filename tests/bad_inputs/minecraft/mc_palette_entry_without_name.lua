-- A palette entry without its Name.
-- expect: palette entry 2 has no Name
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local nameless = W.compound{{"Properties", W.compound{}}}
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(4, {"minecraft:stone", nameless})})}})
require("minecraft.world").load{dir = "."}
