-- expect: Lua memory limit of 32.0 MB reached
-- flags: --lua-memory 32M
local t = {}
for i = 1, 1e12 do t[i] = {i} end
