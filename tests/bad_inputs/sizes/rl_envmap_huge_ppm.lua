-- An environment map declaring 100000x100000 pixels (it failed with a bare std::bad_alloc naming no file).
-- expect: torte.light.environment: image 'rl_huge.ppm' (100000x100000, 3 channels) needs ~
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_huge.ppm", "P6\n100000 100000\n255\n" .. ("\x80"):rep(1000))
local l = torte.light.environment{file = "rl_huge.ppm"}
