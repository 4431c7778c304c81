-- 2^30 samples per pixel.
-- expect: torte.render: 'spp' must be in [1, 16777216], got 1073741824
local s = torte.scene()
s:add(torte.shape.sphere{radius = 1})
torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
             width = 8, height = 8, spp = 1 << 30}
