-- expect: debug.setupvalue: the upvalues of C functions are not accessible
-- gmatch's iterator trusts its upvalues to be its own state.
local it = string.gmatch("a b", "%a")
debug.setupvalue(it, 1, 42)
