-- expect: torte.camera.orthographic: 'extent' must be positive
-- 1e39 is a finite number in Lua but infinite as a float.
local _ = torte.camera.orthographic{extent = 1e39}
