-- A PNG texture whose compressed pixel data is overwritten in the middle (its CRC no longer matches).
-- expect: cannot read image texture 'rl_bad.png'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, picture, textured = case.write, case.picture, case.textured
picture("rl_good.png")
local f = assert(io.open("rl_good.png", "rb"))
local d = f:read("a")
f:close()
local mid = #d // 2
write("rl_bad.png", d:sub(1, mid) .. ("\xff"):rep(64) .. d:sub(mid + 65))
local t = torte.texture.image{file = "rl_bad.png"}
textured(t)
