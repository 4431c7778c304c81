-- 12 subdivision levels of 200 triangles (8.4e9): refused up front by the count, not level by level.
-- expect: torte.mesh.subdivide: 12 levels of 200 triangles would give 3.36e+09 triangles, more than the limit of 2^31
-- timeout: 20
local case = require "case"  -- tests/bad_inputs/lib/case.lua
local write = case.write
local lines = {}
for j = 0, 10 do for i = 0, 10 do lines[#lines + 1] = ("v %d %d 0"):format(i, j) end end
for j = 0, 9 do for i = 1, 10 do
  local a = j * 11 + i
  lines[#lines + 1] = ("f %d %d %d %d"):format(a, a + 1, a + 12, a + 11)
end end
write("rl_grid.obj", table.concat(lines, "\n") .. "\n")
local m = torte.mesh.load("rl_grid.obj")
local big = m:subdivide{levels = 12}
