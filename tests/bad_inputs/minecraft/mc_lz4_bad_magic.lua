-- An LZ4 (type 4) chunk without the LZ4Block magic.
-- expect: LZ4 block 1 at byte 0: bad magic
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.region("r.0.0.mca", {{0, 0, "LZ5Block" .. ("\0"):rep(40), compression = 4}})
require("minecraft.world").load{dir = "."}
