-- expect: torte.light.point: 'position' must lie within +-1e18
local _ = torte.light.point{position = {0, 1e30, 0}}
