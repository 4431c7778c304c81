-- An OBJ face index of 100,000 bytes: quoted up to 40 characters, with its length.
-- expect: rl_long.obj: line 4: bad vertex index '7777777777777777777777777777777777777777'... (100000 bytes)
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_long.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 " .. ("7"):rep(100000) .. "\n")
local m = torte.mesh.load("rl_long.obj")
