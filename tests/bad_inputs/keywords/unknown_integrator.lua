-- expect: must be "path", "direct", "igi", "lt", "bdpt", "vcm", "ppm" or "mlt", got "metropolis"
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, emission = 1})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1,
             integrator = "metropolis"}
