-- A PNG texture whose compressed pixel data is overwritten in the middle (its CRC no longer matches).
-- expect: cannot read image texture 'rl_bad.png'
local function picture(file)  -- a noisy 64x64 render written by torte itself (it compresses little)
  local s = torte.scene()
  s:add(torte.shape.sphere{radius = 1})
  s:add(torte.light.infinite{radiance = {1, 0.8, 0.6}})
  torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
               width = 64, height = 64, spp = 1}:write(file)
end
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
picture("rl_good.png")
local f = assert(io.open("rl_good.png", "rb"))
local d = f:read("a")
f:close()
local mid = #d // 2
write("rl_bad.png", d:sub(1, mid) .. ("\xff"):rep(64) .. d:sub(mid + 65))
local t = torte.texture.image{file = "rl_bad.png"}
textured(t)
