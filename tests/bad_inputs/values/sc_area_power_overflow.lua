-- expect: its emitted power is infinite in float; lower its intensity (or the emitter's size)
-- where: sc_area_power_overflow\.lua:[0-9]+: torte\.render: torte\.shape\.sphere at .*sc_area_power_overflow\.lua:5:
-- Each value is in range, their product (pi * area * radiance) is not: the error names the emitter.
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1e16, emission = 1e20})
scene:add(torte.shape.sphere{radius = 1e16, emission = 1e20, transform = torte.translate(0, 1e17, 0)})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5e16}}, width = 4, height = 4, spp = 1}
