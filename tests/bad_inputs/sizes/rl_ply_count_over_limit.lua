-- A PLY declaring more vertices than 32-bit indices can address.
-- expect: rl_many.ply: the header declares 5000000000 vertices, more than the limit of 4294967295 (2^32 - 1)
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, ply_head = case.write, case.ply_head
write("rl_many.ply", ply_head("ascii", 5000000000, 1) .. "0 0 0\n")
local m = torte.mesh.load("rl_many.ply")
