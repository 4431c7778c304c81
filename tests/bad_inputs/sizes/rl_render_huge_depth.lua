-- A path depth of a million.
-- expect: torte.render: 'max_depth' must be in [0, 10000], got 1000000
local s = torte.scene()
s:add(torte.shape.sphere{radius = 1})
torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
             width = 8, height = 8, max_depth = 1000000}
