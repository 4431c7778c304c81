-- expect: precompiled Lua chunks are not accepted
-- The same chunk handed over by a reader function, in two pieces.
local bytes = string.dump(function() return 1 end)
local pieces = {bytes:sub(1, 2), bytes:sub(3)}
local f = assert(load(function() return table.remove(pieces, 1) end, "=pieces", "bt"))
