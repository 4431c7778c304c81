-- A section whose Palette is an int.
-- expect: section Y=4: the palette is not a list
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local section = W.compound{{"Y", W.byte(4)}, {"Palette", W.int(3)}, {"BlockStates", W.longs(256)}}
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {section})}})
require("minecraft.world").load{dir = "."}
