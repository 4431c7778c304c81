-- A binary PPM texture whose pixels stop after 100 of 64x64 (it used to render black silently).
-- expect: cannot read image texture 'rl_cut.ppm': the pixel data is truncated or corrupt
local function write(name, bytes)
  local f = assert(io.open(name, "wb"))
  f:write(bytes)
  f:close()
end
local function textured(tex)  -- renders a sphere with the texture, so its lookups happen
  local s = torte.scene()
  s:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = tex}})
  s:add(torte.light.point{position = {0, 2, -4}, intensity = {20, 20, 20}})
  return torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
                      width = 16, height = 16, spp = 1}
end
write("rl_cut.ppm", "P6\n64 64\n255\n" .. ("\x80\x40\x20"):rep(100))
local t = torte.texture.image{file = "rl_cut.ppm"}
textured(t)
