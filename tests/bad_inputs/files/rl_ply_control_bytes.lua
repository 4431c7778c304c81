-- A PLY header keyword holding a NUL and an escape sequence: quoted with escapes, not sent to the terminal.
-- expect: rl_ctl.ply: header line 3: unknown keyword 'elem\x00ent\x1b[2J'
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
write("rl_ctl.ply", "ply\nformat ascii 1.0\nelem\0ent\27[2J vertex 3\nend_header\n")
local m = torte.mesh.load("rl_ctl.ply")
