-- expect: torte.camera.orthographic: 'up' must not be parallel
-- A tiny up vector is judged by its direction, not its length.
local _ = torte.camera.orthographic{eye = {0, 0, -5}, look_at = {0, 0, 5}, up = {0, 0, -1e-30}}
