-- A chunk whose (uncompressed) payload is text, not NBT.
-- expect: torte.data.nbt: unknown root tag type 104
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, "hello world"}})
require("minecraft.world").load{dir = "."}
