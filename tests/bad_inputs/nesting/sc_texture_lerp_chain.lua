-- expect: torte.texture.lerp: the texture expression nests
-- lerp nests through any of its three arguments.
local T = torte.texture
local t = T.checker{a = 0, b = 1}
for _ = 1, 3000 do t = T.lerp{t = T.checker{a = 0.2, b = 0.8}, a = t, b = 0.5} end
