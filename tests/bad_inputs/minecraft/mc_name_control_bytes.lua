-- A block name holding a line break and an escape byte, in an entry with bad Properties: the message stays one
-- line of printable text.
-- expect: palette entry 1 (minecraft:stone\x0a\x1b[31m): Properties is a number, not a compound
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local entry = W.compound{{"Name", W.string("minecraft:stone\n\27[31m")}, {"Properties", W.int(1)}}
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, {W.section(4, {entry})})}})
require("minecraft.world").load{dir = "."}
