-- Ten thousand small emitters: a 100 x 100 grid of glowing beads of many colours hanging over a floor, with
-- matte and plastic spheres among them, under a faint sky. The scene for many-light sampling (the light BVH,
-- docs/lights-and-sampling.md): by power alone each shading point gets a bead from anywhere on the grid, mostly
-- far away; the light BVH picks the beads near it.
--
--   torte scenes/many-lights.lua [width=480] [height=270] [spp=16] [max_depth=5]
--                                [light_sampler=bvh|power] [integrator=path|direct] [output=out/many-lights.exr]
local torte = require "torte"

local opt = torte.options{
  width = 480, height = 270, spp = 16, max_depth = 5, integrator = "path", light_sampler = "bvh",
  output = "out/many-lights.exr", seed = 0,
}

local scene = torte.scene()
local T = torte.translate
scene:add(torte.shape.polygon{
  points = {{-12, 0, -12}, {-12, 0, 12}, {12, 0, 12}, {12, 0, -12}},
  material = torte.material.matte{color = {0.6, 0.6, 0.6}},
})

-- Beads: a deterministic hash picks each one's colour and height.
local n = 100
local bead_material = torte.material.matte{color = {0.2, 0.2, 0.2}}
for i = 0, n - 1 do
  for j = 0, n - 1 do
    local h = ((i * 73856093) ~ (j * 19349663)) % 1000 / 1000
    local hue = ((i * 31 + j * 17) % 6)
    local c = ({{1, 0.3, 0.1}, {1, 0.8, 0.2}, {0.2, 1, 0.4}, {0.2, 0.5, 1}, {0.9, 0.3, 1}, {1, 1, 1}})[hue + 1]
    local e = 1.2
    scene:add(torte.shape.sphere{
      radius = 0.04, material = bead_material, emission = {c[1] * e, c[2] * e, c[3] * e},
      transform = T(-10 + 20 * (i + 0.5) / n, 0.4 + 0.8 * h, -10 + 20 * (j + 0.5) / n),
    })
  end
end

for k = 0, 6 do
  local x, z = -6 + 2 * k, -2 + (k % 3) * 2
  local m = k % 2 == 0 and torte.material.matte{color = {0.8, 0.75, 0.7}}
                        or torte.material.plastic{color = {0.3, 0.4, 0.8}, roughness = 0.2}
  scene:add(torte.shape.sphere{radius = 0.7, material = m, transform = T(x, 0.7, z)})
end
scene:add(torte.light.infinite{radiance = {0.02, 0.025, 0.04}})

local camera = torte.camera.perspective{eye = {0, 4.5, -13}, look_at = {0, 0.3, 0}, fov = 40}
local image = torte.render{scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
                           max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed,
                           light_sampler = opt.light_sampler}
torte.save(image, opt.output)
