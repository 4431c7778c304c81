-- expect: -
-- sigint: 3
-- timeout: 10
-- The first Ctrl-C stops Lua code too: exit 130, no error.
while true do end
