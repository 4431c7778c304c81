-- expect: torte.material.mix: the material nests 65 levels of mix/bump materials; the limit is 64
-- A mix{} chain 36,000 deep overflowed the C stack when the scene was flattened; it is refused at level 65.
local m = torte.material.matte{}
for _ = 1, 36000 do m = torte.material.mix{a = m, b = torte.material.matte{}} end
