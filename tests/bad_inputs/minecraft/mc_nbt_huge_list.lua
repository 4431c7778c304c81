-- An NBT list declaring 2^31-1 compounds in a few bytes.
-- expect: list of 2147483647 entries needs 2147483647 bytes
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local huge = {9, string.pack(">Bi4", 10, 0x7fffffff)}
W.region("r.0.0.mca", {{0, 0, W.nbt(W.compound{{"DataVersion", W.int(2566)}, {"Level", W.compound{{"Sections", huge}}}})}})
require("minecraft.world").load{dir = "."}
