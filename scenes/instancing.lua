-- Instancing: a recursive fractal of frames. Level 0 is the Stanford dragon (a sphere when ../shared/data is
-- absent); level k places six copies of level k-1, scaled by 0.45, on a ring around a seventh one raised in the
-- middle, so `levels=4` shows 7^4 = 2,401 dragons (240 M triangles as placed) from one dragon's memory. Each level
-- is a group built with scene:frame / torte.group and placed with torte.instance.
--
--   torte scenes/instancing.lua [levels=4] [width=800] [height=500] [spp=32] [max_depth=6]
--                               [integrator=path|direct|lt] [data=<meshes directory>] [output=out/instancing.exr]
local torte = require "torte"

local script_dir = torte.script_dir  -- absolute: the paths below do not depend on the working directory
local opt = torte.options{
  levels = 4, width = 800, height = 500, spp = 32, max_depth = 6, integrator = "path", seed = 0,
  data = script_dir .. "/../../shared/data/meshes", output = "out/instancing.exr",
}
if opt.levels < 0 or opt.levels > 8 or opt.levels ~= math.floor(opt.levels) then
  error(("argument 'levels' must be an integer in [0, 8], got %s"):format(opt.levels))
end

local T, S, R = torte.translate, torte.scale, torte.rotate
local M = torte.material

-- Level 0: one dragon standing on y = 0, about one unit wide.
local base = torte.group()
local path = opt.data .. "/dragon/dragon_100k_binary_le.ply"
local file = io.open(path, "rb")
if file then
  file:close()
  local dragon = torte.mesh.load(path):smooth_normals()
  base:add(torte.shape.mesh{mesh = dragon, material = M.plastic{color = {0.7, 0.25, 0.08}, roughness = 0.25},
                            transform = dragon:fit{width = 1, floor = true}})
else
  io.stderr:write(("instancing.lua: %s not found (../shared/data absent?); using spheres\n"):format(path))
  base:add(torte.shape.sphere{radius = 0.4, transform = T(0, 0.4, 0), material = M.plastic{color = {0.7, 0.25, 0.08}}})
end

-- Level k: a frame holding six level k-1 groups on a ring and one in the middle, raised on a gold pedestal.
local pedestal = M.metal{metal = "gold", roughness = 0.3}
local level = base
for k = 1, opt.levels do
  local previous = level
  level = torte.group()
  for i = 0, 5 do
    local a = i * 60
    level:add(torte.instance{group = previous, transform = R(a, {0, 1, 0}) * T(0.8, 0, 0) * R(-90 - a * 0.5, {0, 1, 0}) * S(0.45)})
  end
  level:frame(S(0.5), function(center)  -- a nested frame: the middle copy on a pedestal
    center:add(torte.instance{group = previous, transform = T(0, 0.3, 0)})
    center:add(torte.shape.cylinder{radius = 0.45, z_min = 0, z_max = 0.3, transform = R(-90, {1, 0, 0}), material = pedestal})
    center:add(torte.shape.disk{radius = 0.45, transform = T(0, 0.3, 0) * R(-90, {1, 0, 0}), material = pedestal})
  end)
  -- Scale the whole level back to about one unit wide.
  local wrapped = torte.group()
  wrapped:add(torte.instance{group = level, transform = S(0.55)})
  level = wrapped
end

local scene = torte.scene()
scene:add(torte.instance{group = level, transform = S(2.2)})
scene:add(torte.shape.polygon{points = {{-30, 0, -30}, {-30, 0, 30}, {30, 0, 30}, {30, 0, -30}},
                              material = M.matte{color = {0.5, 0.5, 0.52}}})
scene:add(torte.shape.sphere{radius = 1.5, transform = T(-3, 6, -3), emission = {12, 11, 10},
                             material = M.matte{color = 0}})
scene:add(torte.light.infinite{radiance = {0.25, 0.28, 0.35}})

local camera = torte.camera.perspective{eye = {0, 1.9, -2.9}, look_at = {0, 0.25, 0}, fov = 40}
local image = torte.render{
  scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
  max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed,
}
torte.save(image, opt.output)
