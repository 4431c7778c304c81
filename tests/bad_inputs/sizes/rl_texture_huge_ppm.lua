-- A PPM texture declaring 100000x100000 pixels with a few bytes of data.
-- expect: image texture 'rl_huge.ppm' (100000x100000, 3 channels) needs ~
-- timeout: 30
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
write("rl_huge.ppm", "P6\n100000 100000\n255\n" .. ("\x80"):rep(1000))
local t = torte.texture.image{file = "rl_huge.ppm"}
textured(t)
