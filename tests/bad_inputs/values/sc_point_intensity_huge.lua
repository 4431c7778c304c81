-- expect: torte.light.point: 'intensity' must be at most 1e20 per channel
-- 3e38 is finite, but the light's power (4 pi I) overflowed: "distribution weight 0 is inf", no light named.
local _ = torte.light.point{position = {0, 1, 0}, intensity = 3e38}
