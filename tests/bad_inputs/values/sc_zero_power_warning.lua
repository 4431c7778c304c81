-- warning
-- expect: torte.render: every light of the scene has zero power: the image is black
local scene = torte.scene()
scene:add(torte.shape.sphere{}, torte.light.point{position = {0, 3, 0}, intensity = 0})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
