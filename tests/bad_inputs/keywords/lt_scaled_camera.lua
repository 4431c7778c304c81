-- expect: cannot be used with integrator "lt"
-- A camera placed by a scaling transform: light paths cannot be connected to it (camera space distances differ).
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, emission = 1})
torte.render{scene = scene, camera = torte.camera.perspective{transform = torte.scale(2)}, width = 4, height = 4,
             spp = 1, integrator = "lt"}
