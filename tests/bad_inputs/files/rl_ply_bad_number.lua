-- An ASCII PLY vertex with a control byte where a number belongs.
-- expect: rl_bad.ply: vertex 1 of 3 (line 11): '1\x07' is not a valid number
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
write("rl_bad.ply", ply_head("ascii", 3, 1) .. "0 0 0\n1\7 0 0\n0 1 0\n3 0 1 2\n")
local m = torte.mesh.load("rl_bad.ply")
