-- A scale test: Stanford's Lucy grown by midpoint subdivision (with a small random displacement, so the scan
-- gains fine detail) to tens of millions of triangles, with the dragon and the bunny beside her, on a matte
-- floor under an area light and a sky.
--
--   torte scenes/lucy-scale.lua [levels=4] [displacement=0.05] [companions=true] [mesh=<hero .ply/.obj>]
--                               [data=<meshes directory>] [width=800] [height=600] [spp=16] [max_depth=5]
--                               [integrator=path|direct|lt] [output=out/lucy-scale.exr]
--                               [save_ply=<directory>] [ply_dir=<directory>]
--                               [bvh_layout=auto|default|packed|compact] [memory_budget=<size, e.g. 1.5GB>]
--
-- Triangles: the hero is subdivided `levels` times (x4 each), the companions max(levels - 2, 0) times.
--   levels=4 (default): Lucy 99,970 x 256 = 25,592,320 + dragon 100,000 x 16 = 1,600,000
--                       + bunny 69,451 x 16 = 1,111,216, in all 28,303,536 triangles (>= 28 M).
--   (No single model here reaches 28 M at 4 levels - 100 k x 256 = 25.6 M - and 5 levels make 102 M.)
--   levels=0: the scans as they are, 269,421 triangles, for quick tests.
-- The models come from ../shared/data/meshes (relative to the repository root); `data` overrides the
-- directory, `mesh` the hero model (relative paths are relative to the current directory).
-- `save_ply` writes every grown model to <directory>/<model>.ply (mesh:save); `ply_dir` loads them from there
-- instead of growing them (scripts/bench-lucy-ply.sh measures that path's memory).
-- `bvh_layout` and `memory_budget` choose the triangles' layout (torte.scene in docs/lua-api.md): with
-- memory_budget=1.5GB the default layout's estimate exceeds the budget and the packed one is built;
-- memory_budget=1GB leaves only the compact one.
local torte = require "torte"

-- This script's directory, so the default data path works from any current directory.
local script_dir = torte.script_dir  -- absolute: the paths below do not depend on the working directory

local opt = torte.options{
  levels = 4, displacement = 0.05, companions = true, mesh = "", data = script_dir .. "/../../shared/data/meshes",
  width = 800, height = 600, spp = 16, max_depth = 5, integrator = "path", output = "out/lucy-scale.exr",
  seed = 0, save_ply = "", ply_dir = "", bvh_layout = "auto", memory_budget = "",
}
if opt.levels < 0 or opt.levels ~= math.floor(opt.levels) then
  error(("argument 'levels' must be a non-negative integer, got %s"):format(opt.levels))
end

local T, S, R = torte.translate, torte.scale, torte.rotate
local total_triangles = 0

-- Loads and subdivides one model; returns the mesh and a transform that stands it on the floor (y = 0) with
-- its footprint centred on (x, z), scaled to `height`, turned by `yaw` degrees.
local function place(path, levels, height, x, z, yaw)
  local name = path:match("[^/\\]*$"):gsub("%.%w+$", "")
  if opt.ply_dir ~= "" then path, levels = opt.ply_dir .. "/" .. name .. ".ply", 0 end
  local t0 = torte.clock()
  local base = torte.mesh.load(path)
  local t1 = torte.clock()
  local mesh = levels > 0 and base:subdivide{levels = levels, displacement = opt.displacement, seed = opt.seed}
               or base
  local t2 = torte.clock()
  if opt.save_ply ~= "" then mesh:save(opt.save_ply .. "/" .. name .. ".ply") end
  print(("%s: %d triangles loaded in %.3f s; %d levels -> %d triangles, %d vertices in %.2f s"):format(
    path:match("[^/\\]*$"), base.triangles, t1 - t0, levels, mesh.triangles, mesh.vertices, t2 - t1))
  total_triangles = total_triangles + mesh.triangles
  local lo, hi = mesh:bounds()
  local s = height / (hi[2] - lo[2])
  local to_origin = T(-(lo[1] + hi[1]) / 2, -lo[2], -(lo[3] + hi[3]) / 2)
  return mesh, T(x, 0, z) * R(yaw, {0, 1, 0}) * S(s) * to_origin
end

local scene = torte.scene{bvh_layout = opt.bvh_layout,
                          memory_budget = opt.memory_budget ~= "" and opt.memory_budget or nil}
local statue = torte.material.matte{color = {0.75, 0.72, 0.68}}
local stone = torte.material.matte{color = {0.55, 0.56, 0.6}}

local hero_path = opt.mesh ~= "" and opt.mesh or opt.data .. "/lucy/lucy_100k.obj"
-- Turned 180 degrees: the Stanford scan faces +z, away from the camera.
local hero, hero_tf = place(hero_path, opt.levels, 2.0, 0, 0, 180)
scene:add(torte.shape.mesh{mesh = hero, transform = hero_tf, material = statue})
-- Everything in world space lies within x, z in [-extent, extent] and y in [0, 2].
local extent = 1.2
if opt.companions then
  local side = math.max(opt.levels - 2, 0)
  local dragon, dragon_tf = place(opt.data .. "/dragon/dragon_100k_binary_le.ply", side, 0.7, -1.05, 0.5, 30)
  scene:add(torte.shape.mesh{mesh = dragon, transform = dragon_tf, material = statue})
  local bunny, bunny_tf = place(opt.data .. "/bunny/bun_zipper.ply", side, 0.6, 1.0, 0.5, -20)
  scene:add(torte.shape.mesh{mesh = bunny, transform = bunny_tf, material = statue})
  extent = 1.6
end
print(("lucy-scale: %d triangles in all"):format(total_triangles))

-- Floor, a warm area light above front-left (its front faces down), and a pale sky.
scene:add(torte.shape.polygon{
  points = {{-8, 0, -8}, {-8, 0, 8}, {8, 0, 8}, {8, 0, -8}}, material = stone,
})
scene:add(torte.shape.polygon{
  points = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}},
  transform = T(2.5, 4.5, -3) * R(35, {1, 0, 1}), emission = {24, 21, 17},
  material = torte.material.matte{color = 0},
})
scene:add(torte.light.infinite{radiance = {0.25, 0.3, 0.4}})

-- Frame the group: look at its middle from the front and a little above, far enough back for the horizontal
-- field of view to hold it (and the vertical one, for tall images).
local fov = 35
local target = {0, 0.95, 0.2}
local half = math.max(extent, 1.2 * opt.height / opt.width) + 0.3
local distance = half / math.tan(math.rad(fov / 2))
local camera = torte.camera.perspective{
  eye = {0, 0.95 + 0.12 * distance, target[3] - distance}, look_at = target, fov = fov, fov_axis = "horizontal",
}

local image = torte.render{
  scene = scene, camera = camera,
  width = opt.width, height = opt.height, spp = opt.spp, max_depth = opt.max_depth,
  integrator = opt.integrator, seed = opt.seed,
  -- The sky's power grows with the scene's size: picking one light by power would starve the area light.
  sample_all_lights = true,
}
torte.save(image, opt.output)
