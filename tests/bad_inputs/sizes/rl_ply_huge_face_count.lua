-- An ASCII PLY declaring 900 billion faces after 3 vertices.
-- expect: rl_faces.ply: face 1 of 900000000000: file ends early (the header declares 900000000000
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, ply_head = case.write, case.ply_head
write("rl_faces.ply", ply_head("ascii", 3, 900000000000) .. "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
local m = torte.mesh.load("rl_faces.ply")
