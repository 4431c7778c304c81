-- expect: image:write: 'elsewhere/x.exr'
-- flags: --sandbox
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1})
scene:add(torte.light.infinite{radiance = 1})
local img = torte.render{scene = scene, camera = torte.camera.perspective{}, width = 2, height = 2, spp = 1}
torte.save(img, "elsewhere/x.exr")
