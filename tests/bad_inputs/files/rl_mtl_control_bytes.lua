-- An MTL colour with control bytes instead of numbers.
-- expect: rl_bad.mtl: line 2: '\x03\x04' is not a number
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_bad.mtl", "newmtl red\nKd 1 \3\4 0\n")
write("rl_m.obj", "mtllib rl_bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n")
local m = torte.mesh.load("rl_m.obj")
