-- A pre-1.13 section whose Blocks array holds 100 bytes instead of 4096.
-- expect: section Y=4: Blocks is not a 4096-byte array
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local section = W.compound{{"Y", W.byte(4)}, {"Blocks", W.bytes(("\1"):rep(100))}, {"Data", W.bytes(("\0"):rep(2048))}}
local level = W.compound{{"xPos", W.int(0)}, {"zPos", W.int(0)}, {"Sections", W.list{section}}}
W.region("r.0.0.mca", {{0, 0, W.nbt(W.compound{{"DataVersion", W.int(1343)}, {"Level", level}})}})
require("minecraft.world").load{dir = "."}
