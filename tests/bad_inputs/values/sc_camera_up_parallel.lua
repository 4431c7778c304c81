-- expect: torte.camera.perspective: 'up' must not be parallel to the viewing direction (look_at - eye)
local _ = torte.camera.perspective{eye = {0, 5, 0}, look_at = {0, 0, 0}, up = {0, 1, 0}}
