-- An ASCII PLY whose header declares 8 vertices and that ends after 3.
-- expect: rl_cut.ply: vertex 3 of 8: file ends early
local function write(name, bytes)
  local f = assert(io.open(name, "wb"))
  f:write(bytes)
  f:close()
end
local function ply_head(format, vertices, faces)
  return "ply\nformat " .. format .. " 1.0\nelement vertex " .. vertices ..
         "\nproperty float x\nproperty float y\nproperty float z\n" ..
         (faces and "element face " .. faces .. "\nproperty list uchar int vertex_indices\n" or "") .. "end_header\n"
end
write("rl_cut.ply", ply_head("ascii", 8, 2) .. "0 0 0\n1 0 0\n0 1 0\n")
local m = torte.mesh.load("rl_cut.ply")
