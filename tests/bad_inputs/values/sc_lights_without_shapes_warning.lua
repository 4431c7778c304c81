-- warning
-- expect: the scene has no shapes and no light at infinity (infinite, environment, sky): the image is black
local scene = torte.scene()
scene:add(torte.light.point{position = {0, 3, 0}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
