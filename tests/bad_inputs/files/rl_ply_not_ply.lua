-- A .ply file that holds something else.
-- expect: rl_text.ply: not a PLY file (the first line is not 'ply')
local function write(name, bytes)
  local f = assert(io.open(name, "wb"))
  f:write(bytes)
  f:close()
end
write("rl_text.ply", "solid cube\nfacet normal 0 0 1\n")
local m = torte.mesh.load("rl_text.ply")
