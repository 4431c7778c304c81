-- expect: torte.render: 'bvh_layout' must be "auto", "default", "packed" or "compact", got "small"
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = 0.5}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1,
             bvh_layout = "small"}
