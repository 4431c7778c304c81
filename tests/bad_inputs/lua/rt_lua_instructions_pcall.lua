-- expect: Lua instructions, its limit
-- flags: --lua-instructions 1000000
-- pcall cannot swallow the limit: the first instruction after it raises again.
while true do pcall(function() while true do end end) end
