-- A "PNG" texture that is text.
-- expect: cannot read image texture 'rl_text.png'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_text.png", ("not an image\n"):rep(20))
local t = torte.texture.image{file = "rl_text.png"}
