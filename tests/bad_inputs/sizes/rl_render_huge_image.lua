-- A 100000x100000 render: refused by its pixel count before the scene is built.
-- expect: torte.render: 'width' x 'height' = 100000x100000 = 10000000000 pixels, more than the limit of 268435456 (2^28)
local s = torte.scene()
s:add(torte.shape.sphere{radius = 1})
torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
             width = 100000, height = 100000}
