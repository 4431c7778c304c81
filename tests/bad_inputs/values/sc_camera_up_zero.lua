-- expect: torte.camera.perspective: 'up' must be a non-zero vector
-- up = {0, 0, 0} rendered a black image.
local _ = torte.camera.perspective{eye = {0, 1, -5}, look_at = {0, 0, 0}, up = {0, 0, 0}}
