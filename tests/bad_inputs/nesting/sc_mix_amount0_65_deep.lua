-- expect: the material nests 65 levels of mix/bump materials; the limit is 64
-- mix{amount = 0} 65 deep (always picks 'a') hung the render; refused when the 65th level is made.
local m = torte.material.matte{}
for _ = 1, 65 do m = torte.material.mix{a = m, b = torte.material.mirror{}, amount = 0} end
