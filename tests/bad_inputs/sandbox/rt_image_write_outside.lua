-- expect: may not be written under --sandbox
-- flags: --sandbox
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1})
scene:add(torte.light.infinite{radiance = 1})
local img = torte.render{scene = scene, camera = torte.camera.perspective{}, width = 2, height = 2, spp = 1}
img:write("/tmp/rt_image_write_outside.png")
