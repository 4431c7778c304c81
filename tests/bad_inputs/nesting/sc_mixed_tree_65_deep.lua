-- expect: torte.material.mix: the material nests 65 levels
-- The deeper side of a mix counts: a 64-deep bump chain under one more mix is one level too many.
local m = torte.material.plastic{}
for _ = 1, 64 do m = torte.material.bump{material = m, height = 0.01} end
local shallow = torte.material.matte{}
local _ = torte.material.mix{a = shallow, b = m}
