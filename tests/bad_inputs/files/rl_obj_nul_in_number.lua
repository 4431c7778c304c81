-- An OBJ vertex whose number holds a NUL byte: the message shows it escaped, not cut short at the NUL.
-- expect: rl_nul.obj: line 2: '1.5\x00junk' is not a number
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_nul.obj", "v 0 0 0\nv 1.5\0junk 0 0\n")
local m = torte.mesh.load("rl_nul.obj")
