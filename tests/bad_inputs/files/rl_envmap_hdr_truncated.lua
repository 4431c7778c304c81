-- An environment map in Radiance HDR cut in half.
-- expect: torte.light.environment: cannot read image 'rl_cut.hdr'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local cut, picture = case.cut, case.picture
picture("rl_good.hdr")
cut("rl_good.hdr", "rl_cut.hdr", 0.5)
local l = torte.light.environment{file = "rl_cut.hdr"}
