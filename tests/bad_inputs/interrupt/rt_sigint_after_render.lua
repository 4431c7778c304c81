-- expect: -
-- sigint: 3
-- timeout: 40
-- After the render, the script has a grace period to save; one that runs on is stopped after it.
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1})
scene:add(torte.light.infinite{radiance = 1})
local img = torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -4}},
                         width = 64, height = 64, spp = 16777216}
assert(img.interrupted, "the render was stopped by Ctrl-C")
while true do end
