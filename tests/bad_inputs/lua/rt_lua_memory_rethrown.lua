-- expect: Lua memory limit of 32.0 MB reached
-- flags: --lua-memory 32M
-- The script catches Lua's "not enough memory" and raises it again: the message still names the limit.
local ok, err = pcall(string.rep, "x", 1 << 28)
assert(not ok)
error(err)
