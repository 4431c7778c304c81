-- expect: torte.texture operator *: the texture expression nests 1025 levels deep
-- A deep texture meant for a material's colour fails where it is built, not at torte.render.
local T = torte.texture
local c = T.constant{value = {0.5, 0.5, 0.5}}
local t = T.checker{a = c, b = c}
for _ = 1, 1100 do t = t * T.checker{a = 1, b = 1} end
local _ = torte.material.matte{color = t}
