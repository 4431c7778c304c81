-- A zlib (type 2) chunk whose bytes are not a zlib stream.
-- expect: torte.data.inflate: corrupt input
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, ("\x78\x9c") .. ("\255"):rep(200), compression = 2}})
require("minecraft.world").load{dir = "."}
