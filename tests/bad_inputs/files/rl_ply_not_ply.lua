-- A .ply file that holds something else.
-- expect: rl_text.ply: not a PLY file (the first line is not 'ply')
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_text.ply", "solid cube\nfacet normal 0 0 1\n")
local m = torte.mesh.load("rl_text.ply")
