-- expect: integrator 'bdpt': does not support
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = 0.5}})
scene:add(torte.light.infinite{radiance = 1})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1,
             integrator = "bdpt"}
