-- warning
-- expect: torte.render: the scene has no lights and no emitting shapes: the image is black
-- A legitimately black image renders, with one warning line.
local scene = torte.scene()
scene:add(torte.shape.sphere{})
local img = torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
assert(img:mean() == 0)
