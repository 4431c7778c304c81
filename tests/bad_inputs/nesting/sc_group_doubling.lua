-- expect: the nesting of groups places 1073741824 instances; the limit is 268435456
-- 30 levels of groups that each place the one below twice: 2^30 instances, counted before any is made.
local g = torte.group()
g:add(torte.shape.sphere{radius = 0.1})
for _ = 1, 30 do
  local up = torte.group()
  up:add(torte.instance{group = g, transform = torte.translate(0.1, 0, 0)})
  up:add(torte.instance{group = g, transform = torte.translate(0, 0.1, 0)})
  g = up
end
local scene = torte.scene()
scene:add(torte.instance{group = g}, torte.light.point{position = {0, 5, 0}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
