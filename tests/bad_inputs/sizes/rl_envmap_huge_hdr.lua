-- A Radiance HDR environment map declaring 200000x100000 pixels.
-- expect: torte.light.environment: image 'rl_huge.hdr' (200000x100000, 3 channels) needs ~
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n" .. ("\x80"):rep(1000))
local l = torte.light.environment{file = "rl_huge.hdr"}
