-- A chunk's NBT cut in half (its length field says so).
-- expect: torte.data.nbt: truncated input
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local c = W.chunk(0, 0)
W.region("r.0.0.mca", {{0, 0, c:sub(1, #c // 2)}})
require("minecraft.world").load{dir = "."}
