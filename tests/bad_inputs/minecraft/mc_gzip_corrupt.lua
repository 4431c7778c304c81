-- A gzip (type 1) chunk that is not gzip.
-- expect: torte.data.gunzip: corrupt input
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0), compression = 1}})
require("minecraft.world").load{dir = "."}
