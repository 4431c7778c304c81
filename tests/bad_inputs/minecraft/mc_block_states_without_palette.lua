-- A 1.18+ chunk (sections at the root) whose block_states has no palette.
-- expect: section Y=-4: block_states has no palette
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local section = W.compound{{"Y", W.byte(-4)}, {"block_states", W.compound{{"data", W.longs(256)}}}}
W.region("r.0.0.mca", {{0, 0, W.nbt(W.compound{{"DataVersion", W.int(3465)}, {"Status", W.string("minecraft:full")},
                                               {"sections", W.list{section}}})}})
require("minecraft.world").load{dir = "."}
