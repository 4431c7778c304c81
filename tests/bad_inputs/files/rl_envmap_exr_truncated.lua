-- An environment map EXR cut at two thirds.
-- expect: torte.light.environment: cannot read image 'rl_cut.exr'
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
picture("rl_good.exr")
cut("rl_good.exr", "rl_cut.exr", 0.66)
local l = torte.light.environment{file = "rl_cut.exr"}
