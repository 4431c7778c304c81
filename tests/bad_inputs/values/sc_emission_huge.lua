-- expect: torte.shape.disk: 'emission' must be at most 1e20 per channel
local _ = torte.shape.disk{emission = {1e25, 1, 1}}
