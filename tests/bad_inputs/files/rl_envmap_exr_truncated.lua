-- An environment map EXR cut at two thirds.
-- expect: torte.light.environment: cannot read image 'rl_cut.exr'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local cut, picture = case.cut, case.picture
picture("rl_good.exr")
cut("rl_good.exr", "rl_cut.exr", 0.66)
local l = torte.light.environment{file = "rl_cut.exr"}
