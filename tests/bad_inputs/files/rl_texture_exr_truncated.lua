-- An OpenEXR texture cut at two thirds.
-- expect: cannot read image texture 'rl_cut.exr'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local cut, picture, textured = case.cut, case.picture, case.textured
picture("rl_good.exr")
cut("rl_good.exr", "rl_cut.exr", 0.66)
local t = torte.texture.image{file = "rl_cut.exr"}
textured(t)
