-- An OBJ line starting with raw escape sequences (a binary file renamed .obj).
-- expect: rl_bin.obj: line 1: unknown statement '\x1b]0;owned\x07\x01\x02'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_bin.obj", "\27]0;owned\7\1\2 1 2 3\n")
local m = torte.mesh.load("rl_bin.obj")
