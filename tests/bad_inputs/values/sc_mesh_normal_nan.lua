-- expect: torte.shape.mesh: 'normals' entry 2 is not finite
local _ = torte.shape.mesh{positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, indices = {0, 1, 2},
                           normals = {{0, 0, 1}, {0, 0 / 0, 1}, {0, 0, 1}}}
