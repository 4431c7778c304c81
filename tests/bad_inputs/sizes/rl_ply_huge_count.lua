-- A binary PLY declaring 4 billion vertices in a 100-byte body: the count is reported against the file.
-- expect: rl_huge.ply: vertex 8 of 4000000000: file ends early (the header declares 4000000000, which need at least 12 bytes each; 100 bytes follow the header)
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
write("rl_huge.ply", ply_head("binary_little_endian", 4000000000) .. ("\0"):rep(100))
local m = torte.mesh.load("rl_huge.ply")
