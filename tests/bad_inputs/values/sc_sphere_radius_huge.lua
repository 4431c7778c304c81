-- expect: torte.shape.sphere: 'radius' and the transform place the shape beyond +-1e18
local _ = torte.shape.sphere{radius = 1e30}
