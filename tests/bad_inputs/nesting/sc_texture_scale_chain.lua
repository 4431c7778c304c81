-- expect: the texture expression nests 1025 levels deep
-- Products by numbers (scale nodes) nest like sums.
local T = torte.texture
local t = T.perlin{} .. T.xyz{}
for _ = 1, 5000 do t = t * 0.9999 end
