-- An OpenEXR texture cut at two thirds.
-- expect: cannot read image texture 'rl_cut.exr'
local function picture(file)  -- a noisy 64x64 render written by torte itself (it compresses little)
  local s = torte.scene()
  s:add(torte.shape.sphere{radius = 1})
  s:add(torte.light.infinite{radiance = {1, 0.8, 0.6}})
  torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
               width = 64, height = 64, spp = 1}:write(file)
end
local function cut(src, dst, keep)  -- the first `keep` bytes of src (a fraction of it when keep < 1)
  local f = assert(io.open(src, "rb"))
  local d = f:read("a")
  f:close()
  if keep < 1 then keep = math.floor(#d * keep) end
  f = assert(io.open(dst, "wb"))
  f:write(d:sub(1, keep))
  f:close()
end
local function textured(tex)  -- renders a sphere with the texture, so its lookups happen
  local s = torte.scene()
  s:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = tex}})
  s:add(torte.light.point{position = {0, 2, -4}, intensity = {20, 20, 20}})
  return torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
                      width = 16, height = 16, spp = 1}
end
picture("rl_good.exr")
cut("rl_good.exr", "rl_cut.exr", 0.66)
local t = torte.texture.image{file = "rl_cut.exr"}
textured(t)
