-- expect: error loading module 'mod' from file './mod.lua': ./mod.lua: precompiled Lua chunks are not accepted
-- A precompiled module found by require's file searcher.
local out = assert(io.open("mod.lua", "wb"))
out:write(string.dump(function() return {} end))
out:close()
package.path = "./?.lua"
require "mod"
