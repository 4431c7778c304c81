-- A PPM texture declaring 100000x100000 pixels with a few bytes of data.
-- expect: image texture 'rl_huge.ppm' (100000x100000, 3 channels) needs ~
-- timeout: 30
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, textured = case.write, case.textured
write("rl_huge.ppm", "P6\n100000 100000\n255\n" .. ("\x80"):rep(1000))
local t = torte.texture.image{file = "rl_huge.ppm"}
textured(t)
