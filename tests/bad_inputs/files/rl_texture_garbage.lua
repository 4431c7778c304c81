-- A "PNG" texture that is text.
-- expect: cannot read image texture 'rl_text.png'
local function write(name, bytes)
  local f = assert(io.open(name, "wb"))
  f:write(bytes)
  f:close()
end
write("rl_text.png", ("not an image\n"):rep(20))
local t = torte.texture.image{file = "rl_text.png"}
