-- A PNG texture whose header declares 100000x100000 pixels: refused before anything is read (OpenImageIO's
-- failed allocation used to leave a render thread waiting forever).
-- expect: image texture 'rl_huge.png' (100000x100000, 3 channels) needs ~
-- timeout: 30
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, textured = case.write, case.textured
local function crc32(s)  -- for PNG chunks
  local c = 0xffffffff
  for i = 1, #s do
    c = c ~ s:byte(i)
    for _ = 1, 8 do c = (c >> 1) ~ (0xedb88320 & -(c & 1)) end
  end
  return c ~ 0xffffffff
end
local function chunk(kind, data) return string.pack(">I4", #data) .. kind .. data .. string.pack(">I4", crc32(kind .. data)) end
local ihdr = string.pack(">I4I4BBBBB", 100000, 100000, 8, 2, 0, 0, 0)
write("rl_huge.png", "\x89PNG\r\n\x1a\n" .. chunk("IHDR", ihdr) .. chunk("IDAT", "\x78\x01") .. chunk("IEND", ""))
local t = torte.texture.image{file = "rl_huge.png"}
textured(t)
