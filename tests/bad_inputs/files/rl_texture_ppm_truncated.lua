-- A binary PPM texture whose pixels stop after 100 of 64x64 (it used to render black silently).
-- expect: cannot read image texture 'rl_cut.ppm': the pixel data is truncated or corrupt
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, textured = case.write, case.textured
write("rl_cut.ppm", "P6\n64 64\n255\n" .. ("\x80\x40\x20"):rep(100))
local t = torte.texture.image{file = "rl_cut.ppm"}
textured(t)
