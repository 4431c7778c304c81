-- A PLY declaring more vertices than 32-bit indices can address.
-- expect: rl_many.ply: the header declares 5000000000 vertices, more than the limit of 4294967295 (2^32 - 1)
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
write("rl_many.ply", ply_head("ascii", 5000000000, 1) .. "0 0 0\n")
local m = torte.mesh.load("rl_many.ply")
