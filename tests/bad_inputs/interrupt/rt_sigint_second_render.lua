-- expect: -
-- sigint: 3
-- timeout: 20
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1})
scene:add(torte.light.infinite{radiance = 1})
local img = torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -4}},
                         width = 64, height = 64, spp = 16777216}
assert(img.interrupted, "the render was stopped by Ctrl-C")
torte.render{scene = scene, camera = torte.camera.perspective{}, width = 4, height = 4, spp = 1}
error("the second render must not start")
