-- A PNG texture holding only its signature and IHDR chunk.
-- expect: cannot read image texture 'rl_head.png'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local cut, picture, textured = case.cut, case.picture, case.textured
picture("rl_good.png")
cut("rl_good.png", "rl_head.png", 33)
local t = torte.texture.image{file = "rl_head.png"}
textured(t)
