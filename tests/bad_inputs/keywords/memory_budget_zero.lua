-- expect: torte.render: 'memory_budget' must be a positive number of bytes
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = 0.5}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1,
             memory_budget = 0}
