-- A binary PLY declaring 4 billion vertices in a 100-byte body: the count is reported against the file.
-- expect: rl_huge.ply: vertex 8 of 4000000000: file ends early (the header declares 4000000000, which need at least 12 bytes each; 100 bytes follow the header)
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write, ply_head = case.write, case.ply_head
write("rl_huge.ply", ply_head("binary_little_endian", 4000000000) .. ("\0"):rep(100))
local m = torte.mesh.load("rl_huge.ply")
