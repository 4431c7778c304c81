-- An ASCII PLY whose header declares 8 vertices and that ends after 3.
-- expect: rl_cut.ply: vertex 3 of 8: file ends early
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, ply_head = case.write, case.ply_head
write("rl_cut.ply", ply_head("ascii", 8, 2) .. "0 0 0\n1 0 0\n0 1 0\n")
local m = torte.mesh.load("rl_cut.ply")
