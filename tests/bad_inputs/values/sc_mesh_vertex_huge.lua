-- expect: torte.shape.mesh: vertex 1 lies at (1.8e+19, 0, 0), beyond the range +-1e+18 that the scene supports
-- A vertex at 1.8e19 gave "primitive 36 has infinite bounds" without naming the mesh.
local _ = torte.shape.mesh{positions = {{0, 0, 0}, {1.8e19, 0, 0}, {0, 1, 0}}, indices = {0, 1, 2}}
