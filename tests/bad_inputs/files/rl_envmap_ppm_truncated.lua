-- An environment map PPM whose pixels stop early.
-- expect: torte.light.environment: cannot read image 'rl_cut.ppm': the pixel data is truncated or corrupt
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_cut.ppm", "P6\n64 32\n255\n" .. ("\x10\x20\x30"):rep(50))
local l = torte.light.environment{file = "rl_cut.ppm"}
