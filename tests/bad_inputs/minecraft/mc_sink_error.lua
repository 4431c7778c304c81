-- An error of the caller's sink while a chunk loads: the chunk and the script line are both named.
-- expect: mc_sink_error.lua:6: the sink failed
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0)}})
require("minecraft.world").load{dir = ".", sink = function() error("the sink failed") end}
