-- expect: torte.texture.xyz: 'transform' must be invertible (it is singular or not finite)
-- Invertible in double precision, but its inverse overflows float: texture footprints would be infinite.
local _ = torte.texture.xyz{transform = torte.scale(1e-25)}
