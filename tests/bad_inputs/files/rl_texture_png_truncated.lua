-- A PNG texture cut in the middle of its pixel data: an error naming the file when the texture is made
-- (it used to render black, with a libpng line on stderr).
-- expect: cannot read image texture 'rl_cut.png': the pixel data is truncated or corrupt
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local cut, picture, textured = case.cut, case.picture, case.textured
picture("rl_good.png")
cut("rl_good.png", "rl_cut.png", 0.5)
local t = torte.texture.image{file = "rl_cut.png"}
textured(t)
