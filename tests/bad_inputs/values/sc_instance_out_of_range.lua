-- expect: places its group beyond +-1e18, the range the scene supports
local g = torte.group()
g:add(torte.shape.sphere{})
local scene = torte.scene()
scene:add(torte.instance{group = g, transform = torte.translate(3e30, 0, 0)}, torte.light.point{position = {0, 5, 0}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
