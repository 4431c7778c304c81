-- expect: torte.material.bump: the material nests 65 levels of mix/bump materials; the limit is 64
-- bump{} 65 deep made material resolution give up after 64 levels and the render loop forever.
local m = torte.material.matte{}
for _ = 1, 65 do m = torte.material.bump{material = m} end
