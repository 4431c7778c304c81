-- An ASCII PPM texture with a word where a number belongs.
-- expect: cannot read image texture 'rl_bad.ppm'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, textured = case.write, case.textured
write("rl_bad.ppm", "P3\n2 2\n255\n1 2 3 4 5 6\n7 eight 9 10 11 12\n")
local t = torte.texture.image{file = "rl_bad.ppm"}
textured(t)
