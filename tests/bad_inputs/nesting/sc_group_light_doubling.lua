-- expect: the nesting of groups places 2097152 lights; the limit is 1048576
-- Lights placed by nested instances multiply like the instances do.
local g = torte.group()
g:add(torte.light.point{position = {0, 1, 0}})
for _ = 1, 21 do
  local up = torte.group()
  up:add(torte.instance{group = g, transform = torte.translate(0.1, 0, 0)})
  up:add(torte.instance{group = g, transform = torte.translate(0, 0, 0.1)})
  g = up
end
local scene = torte.scene()
scene:add(torte.shape.sphere{}, torte.instance{group = g})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
