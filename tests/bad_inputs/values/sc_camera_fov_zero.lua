-- expect: torte.camera.perspective: 'fov' must be in (0, 180) degrees
local _ = torte.camera.perspective{fov = 0}
