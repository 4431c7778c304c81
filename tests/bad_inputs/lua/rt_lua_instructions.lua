-- expect: the script ran 1000000 Lua instructions, its limit (--lua-instructions N raises it
-- flags: --lua-instructions 1000000
while true do end
