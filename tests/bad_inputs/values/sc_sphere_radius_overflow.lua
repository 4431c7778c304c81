-- expect: torte.shape.sphere: sphere: radius must be positive and finite
-- 1e39 overflows float to infinity.
local _ = torte.shape.sphere{radius = 1e39}
