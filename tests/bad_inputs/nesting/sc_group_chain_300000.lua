-- expect: groups nest more than 32 levels deep
-- A chain of 300,000 groups: refused at torte.render, and released at exit without one destructor per level
-- (which overflowed the C stack).
local g = torte.group()
g:add(torte.shape.sphere{})
for _ = 1, 300000 do
  local up = torte.group()
  up:add(torte.instance{group = g})
  g = up
end
local scene = torte.scene()
scene:add(torte.instance{group = g}, torte.light.point{position = {0, 5, 0}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
