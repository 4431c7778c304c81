-- expect: the script ran 100000 Lua instructions, its limit
-- flags: --sandbox --lua-instructions 100000
local n = 0
while true do n = n + 1 end
