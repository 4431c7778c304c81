-- expect: chunk.luac: precompiled Lua chunks are not accepted
-- Lua skips a first line starting with '#' before it looks for the binary signature.
local out = assert(io.open("chunk.luac", "wb"))
out:write("#!/usr/bin/torte\n", string.dump(function() return 1 end))
out:close()
dofile("chunk.luac")
