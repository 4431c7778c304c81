-- Tiles larger than any image (each one a work unit of a distributed render).
-- expect: torte.render: 'tile_size' must be in [1, 1024], got 4096
local s = torte.scene()
s:add(torte.shape.sphere{radius = 1})
torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
             width = 8, height = 8, tile_size = 4096}
