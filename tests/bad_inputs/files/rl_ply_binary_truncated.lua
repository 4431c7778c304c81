-- A binary PLY cut inside its face list.
-- expect: rl_cut.ply: face 1 of 2: file ends early
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
local v = string.pack("<fff", 0, 0, 0) .. string.pack("<fff", 1, 0, 0) .. string.pack("<fff", 0, 1, 0)
local f = string.pack("<Biii", 3, 0, 1, 2)
write("rl_cut.ply", ply_head("binary_little_endian", 3, 2) .. v .. f .. f:sub(1, 7))
local m = torte.mesh.load("rl_cut.ply")
