-- expect: torte.texture operator +: the texture expression nests 1025 levels deep; the limit is 1024
-- A texture expression 23,000 deep overflowed the C stack when flattened (and would again when evaluated).
local T = torte.texture
local t = T.checker{a = 0.1, b = 0.9}
for _ = 1, 23000 do t = t + 0.001 end
