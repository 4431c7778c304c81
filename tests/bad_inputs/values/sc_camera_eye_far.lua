-- expect: torte.camera.perspective: 'eye' must lie within +-1e18
local _ = torte.camera.perspective{eye = {0, 0, -1e30}, look_at = {0, 0, 0}}
