-- expect: Lua memory limit of 32.0 MB reached
-- flags: --lua-memory 32M
local s = "x"
while true do s = s .. s end
