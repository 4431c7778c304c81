-- expect: vertex 1 lies at (1e+20, 0, 0) once placed by its transform, beyond the range +-1e+18
-- where: sc_mesh_placed_out_of_range\.lua:[0-9]+: torte\.render: torte\.shape\.mesh at .*sc_mesh_placed_out_of_range\.lua:5:
-- Each coordinate is fine, the transform takes the mesh out of range: the error names the mesh and its line.
local scene = torte.scene()
scene:add(torte.shape.mesh{positions = {{0, 0, 0}, {1e10, 0, 0}, {0, 1, 0}}, indices = {0, 1, 2},
                           transform = torte.scale(1e10)})
scene:add(torte.light.point{position = {0, 5, 0}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
