-- An ASCII PLY vertex with a control byte where a number belongs.
-- expect: rl_bad.ply: vertex 1 of 3 (line 11): '1\x07' is not a valid number
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, ply_head = case.write, case.ply_head
write("rl_bad.ply", ply_head("ascii", 3, 1) .. "0 0 0\n1\7 0 0\n0 1 0\n3 0 1 2\n")
local m = torte.mesh.load("rl_bad.ply")
