-- expect: nodes per lookup (a shared sub-texture counts once per use); the limit is 65536
-- t = t + t forty times is small to build but evaluates 2^40 nodes per lookup: refused, not a render that hangs.
local T = torte.texture
local t = T.checker{a = 0.1, b = 0.9}
for _ = 1, 40 do t = t + t end
