-- expect: torte.camera.perspective: 'look_at' must differ from 'eye' (there is no viewing direction)
local _ = torte.camera.perspective{eye = {1, 2, 3}, look_at = {1, 2, 3}}
