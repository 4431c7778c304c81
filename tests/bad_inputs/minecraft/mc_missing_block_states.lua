-- A two-entry palette without block data.
-- expect: 2 palette entries but no block data
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local section = W.compound{{"Y", W.byte(4)}, {"Palette", W.list{W.compound{{"Name", W.string("minecraft:stone")}},
                                                    W.compound{{"Name", W.string("minecraft:dirt")}}}}}
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {section})}})
require("minecraft.world").load{dir = "."}
