-- An ASCII PLY declaring 900 billion faces after 3 vertices.
-- expect: rl_faces.ply: face 1 of 900000000000: file ends early (the header declares 900000000000
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
write("rl_faces.ply", ply_head("ascii", 3, 900000000000) .. "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
local m = torte.mesh.load("rl_faces.ply")
