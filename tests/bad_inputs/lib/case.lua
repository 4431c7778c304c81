-- Helpers shared by the cases of the bad-input catalogue (tests/bad_inputs/README.md): they make the bad files
-- a case needs at run time. A case loads them with `local case = require "case"` (run-case.sh puts this
-- directory on LUA_PATH).
local M = {}

-- Writes `bytes` to the file `name`.
function M.write(name, bytes)
  local f = assert(io.open(name, "wb"))
  f:write(bytes)
  f:close()
end

-- Writes the first `keep` bytes of src to dst (a fraction of src when keep < 1).
function M.cut(src, dst, keep)
  local f = assert(io.open(src, "rb"))
  local d = f:read("a")
  f:close()
  if keep < 1 then keep = math.floor(#d * keep) end
  f = assert(io.open(dst, "wb"))
  f:write(d:sub(1, keep))
  f:close()
end

-- Writes a noisy 64x64 render made by torte itself (it compresses little) to `file`.
function M.picture(file)
  local s = torte.scene()
  s:add(torte.shape.sphere{radius = 1})
  -- A second sphere beside it, so that occlusion and interreflection make noise: a lone convex sphere under a
  -- uniform sky renders noise-free, and its file is then small enough for a cut in half to miss the pixel data.
  s:add(torte.shape.sphere{radius = 0.6, transform = torte.translate(0.9, 0.9, -0.9)})
  s:add(torte.light.infinite{radiance = {1, 0.8, 0.6}})
  torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
               width = 64, height = 64, spp = 1}:write(file)
end

-- Renders a sphere with the texture `tex`, so that its lookups happen.
function M.textured(tex)
  local s = torte.scene()
  s:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = tex}})
  s:add(torte.light.point{position = {0, 2, -4}, intensity = {20, 20, 20}})
  return torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
                      width = 16, height = 16, spp = 1}
end

-- A PLY header: `vertices` xyz float vertices and, when `faces` is given, that many faces.
function M.ply_head(format, vertices, faces)
  return "ply\nformat " .. format .. " 1.0\nelement vertex " .. vertices ..
         "\nproperty float x\nproperty float y\nproperty float z\n" ..
         (faces and "element face " .. faces .. "\nproperty list uchar int vertex_indices\n" or "") .. "end_header\n"
end

-- A raw deflate stream of zeros: 8 x 258 bytes of output for every 13 bytes of input (`copies8` times), a bomb.
function M.deflate_zeros(copies8)
  return "\x63\x18\x05" .. ("\xa3\x60\x14\x8c\x82\x51\x30\x0a\x46\xc1\x28\x18\x05"):rep(copies8) .. "\x00"
end

return M
