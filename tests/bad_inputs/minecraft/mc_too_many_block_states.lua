-- 9 sections of 4096 distinct (unknown) block names each: more block states than 16-bit voxel ids can hold.
-- expect: too many distinct block states for 16-bit voxel ids
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
local W = require "mc_region"  -- tests/bad_inputs/lib/mc_region.lua
local sections = {}
for y = 0, 8 do
  local names = {}
  for i = 1, 4096 do names[i] = ("b%d.%d"):format(y, i) end
  sections[#sections + 1] = W.section(y, names, W.longs(820))  -- 12-bit fields, 5 per long
end
W.region("r.0.0.mca", {{0, 0, W.chunk(0, 0, sections)}})
require("minecraft.world").load{dir = "."}
