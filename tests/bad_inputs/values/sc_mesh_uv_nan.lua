-- expect: torte.shape.mesh: vertex 2 has a non-finite uv (nan, 0)
-- where: sc_mesh_uv_nan\.lua:4:
-- NaN in uvs was accepted (positions and normals were checked): with an image texture, samples turned NaN.
local _ = torte.shape.mesh{positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, indices = {0, 1, 2},
                           uvs = {{0, 0}, {1, 0}, {0 / 0, 0}}}
