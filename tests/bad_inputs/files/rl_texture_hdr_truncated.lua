-- A Radiance HDR texture cut in half.
-- expect: cannot read image texture 'rl_cut.hdr'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local cut, picture, textured = case.cut, case.picture, case.textured
picture("rl_good.hdr")
cut("rl_good.hdr", "rl_cut.hdr", 0.5)
local t = torte.texture.image{file = "rl_cut.hdr"}
textured(t)
