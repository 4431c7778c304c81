-- An OBJ cut in the middle of its last face.
-- expect: rl_cut.obj: line 5: a face needs at least 3 vertices
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_cut.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2")
local m = torte.mesh.load("rl_cut.obj")
