-- expect: chunk.luac: precompiled Lua chunks are not accepted
local out = assert(io.open("chunk.luac", "wb"))
out:write(string.dump(function() return 1 end))
out:close()
dofile("chunk.luac")
