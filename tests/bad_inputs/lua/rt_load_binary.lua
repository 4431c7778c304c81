-- expect: load: precompiled Lua chunks are not accepted, only Lua source text
-- Lua's loader of binary chunks trusts its input; load() takes source text only.
local f = assert(load(string.dump(function() return 1 end)))
