-- A region file of 5000 bytes: shorter than its 8 KiB header.
-- expect: truncated region file: 5000 bytes, the header alone is 8192
-- where: r\.0\.0\.mca: truncated
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
W.write("r.0.0.mca", ("\0"):rep(5000))
require("minecraft.world").load{dir = "."}
