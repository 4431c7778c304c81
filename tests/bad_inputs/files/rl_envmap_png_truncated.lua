-- An environment map PNG cut in half.
-- expect: torte.light.environment: cannot read image 'rl_cut.png': the pixel data is truncated or corrupt
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local cut, picture = case.cut, case.picture
picture("rl_good.png")
cut("rl_good.png", "rl_cut.png", 0.5)
local l = torte.light.environment{file = "rl_cut.png"}
