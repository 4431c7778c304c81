-- An ASCII PPM texture with a word where a number belongs.
-- expect: cannot read image texture 'rl_bad.ppm'
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
write("rl_bad.ppm", "P3\n2 2\n255\n1 2 3 4 5 6\n7 eight 9 10 11 12\n")
local t = torte.texture.image{file = "rl_bad.ppm"}
textured(t)
