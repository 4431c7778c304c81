-- The Happy Buddha in four materials side by side, after Figure 2 of the dort thesis: plastic, metal (gold),
-- glass and mirror, on a matte floor in front of a backdrop, lit by two area lights and a dim sky.
--
--   torte scenes/materials.lua [width=960] [height=360] [spp=64] [max_depth=12]
--                              [integrator=path|direct|lt] [metal=gold] [roughness=0.15]
--                              [mesh=<.ply/.obj>] [data=<meshes directory>] [output=out/materials.exr]
--
-- The model comes from ../shared/data/meshes/happy-buddha (relative to the repository root); `data` overrides
-- the directory and `mesh` the model. Without it the scene falls back to spheres, with a message.
local torte = require "torte"

local script_dir = torte.script_dir  -- absolute: the paths below do not depend on the working directory

local opt = torte.options{
  width = 960, height = 360, spp = 64, max_depth = 12, integrator = "path", seed = 0,
  metal = "gold", roughness = 0.15, mesh = "", data = script_dir .. "/../../shared/data/meshes",
  output = "out/materials.exr",
}

local T, S, R = torte.translate, torte.scale, torte.rotate
local scene = torte.scene()

local materials = {
  torte.material.plastic{color = {0.65, 0.08, 0.06}, roughness = 0.2},
  torte.material.metal{metal = opt.metal, roughness = opt.roughness},
  torte.material.glass{eta = 1.5},
  torte.material.mirror{color = {0.95, 0.95, 0.95}},
}

local path = opt.mesh ~= "" and opt.mesh or opt.data .. "/happy-buddha/happy_vrip_res3.ply"
local file = io.open(path, "rb")
local buddha
if file then
  file:close()
  buddha = torte.mesh.load(path):smooth_normals()  -- the scan has no normals: shade it smooth
else
  io.stderr:write(("materials.lua: %s not found (../shared/data absent?); rendering spheres instead\n"):format(path))
end

-- Four statues 1.6 units tall, 1.3 apart, standing on y = 0.
local height, spacing = 1.6, 1.15
for i, material in ipairs(materials) do
  local x = (2.5 - i) * spacing  -- +x is the image's left: the first material is leftmost
  if buddha then
    scene:add(torte.shape.mesh{mesh = buddha, transform = buddha:fit{height = height, center = {x, 0, 0}, floor = true},
                               material = material})
  else
    scene:add(torte.shape.sphere{radius = 0.5, transform = T(x, 0.5, 0), material = material})
  end
end

-- Floor and a curved-looking backdrop (floor + back wall).
local floor = torte.material.matte{color = {0.55, 0.55, 0.52}}
scene:add(torte.shape.polygon{points = {{-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}, material = floor})
scene:add(torte.shape.polygon{points = {{-20, 0, 3}, {-20, 12, 3}, {20, 12, 3}, {20, 0, 3}},
                              material = torte.material.matte{color = {0.45, 0.47, 0.5}}})

-- Two rectangular area lights, above-front left and right, facing down towards the statues.
local function panel(x, y, z, w, d, radiance)
  scene:add(torte.shape.polygon{
    points = {{x - w, y, z - d}, {x + w, y, z - d}, {x + w, y, z + d}, {x - w, y, z + d}},  -- normal -y
    emission = radiance, material = torte.material.matte{color = 0},
  })
end
panel(2.2, 4.0, -2.0, 0.8, 0.6, {14, 13, 12})
panel(-2.5, 3.5, -1.0, 0.5, 0.5, {10, 11, 13})
scene:add(torte.light.infinite{radiance = {0.08, 0.09, 0.11}})

local camera = torte.camera.perspective{eye = {0, 1.5, -5.6}, look_at = {0, 0.78, 0}, fov = 22}
local image = torte.render{
  scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
  max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed,
}
torte.save(image, opt.output)
