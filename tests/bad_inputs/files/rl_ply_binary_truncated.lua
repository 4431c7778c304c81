-- A binary PLY cut inside its face list.
-- expect: rl_cut.ply: face 1 of 2: file ends early
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, ply_head = case.write, case.ply_head
local v = string.pack("<fff", 0, 0, 0) .. string.pack("<fff", 1, 0, 0) .. string.pack("<fff", 0, 1, 0)
local f = string.pack("<Biii", 3, 0, 1, 2)
write("rl_cut.ply", ply_head("binary_little_endian", 3, 2) .. v .. f .. f:sub(1, 7))
local m = torte.mesh.load("rl_cut.ply")
