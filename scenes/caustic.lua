-- A glass sphere on a matte floor under one small area light: the seed's Figure 2(c) reduced to its essence.
-- Nearly all the light under and beside the sphere is a caustic (light -> glass -> floor -> eye), which camera
-- paths find only by chance: `path` renders it as fireflies, `bdpt` and `vcm` trace it from the light.
--
--   torte scenes/caustic.lua [width=400] [height=300] [spp=64] [max_depth=16]
--                            [integrator=path|direct|lt|bdpt|vcm|ppm|mlt] [radius=0.01] [alpha=0.75] [large_step=0.3]
--                            [eta=1.5] [light_size=0.025] [output=out/caustic.exr]
local torte = require "torte"

local opt = torte.options{
  width = 400, height = 300, spp = 64, max_depth = 16, integrator = "path", seed = 0,
  radius = 0.01, alpha = 0.75, large_step = 0.3, eta = 1.5, light_size = 0.025, time_limit = 0,
  output = "out/caustic.exr",
}

local T = torte.translate
local scene = torte.scene()
local floor = torte.material.matte{color = {0.7, 0.68, 0.64}}
scene:add(torte.shape.polygon{points = {{-6, 0, -6}, {-6, 0, 6}, {6, 0, 6}, {6, 0, -6}}, material = floor})
scene:add(torte.shape.polygon{points = {{-6, 0, 2.5}, {-6, 5, 2.5}, {6, 5, 2.5}, {6, 0, 2.5}},
                              material = torte.material.matte{color = {0.5, 0.52, 0.55}}})
scene:add(torte.shape.sphere{radius = 0.7, transform = T(0, 0.7, 0), material = torte.material.glass{eta = opt.eta}})

-- The light: a small square (half size light_size) high above and a little behind the sphere, facing down (wound
-- so its normal is -y); its power does not depend on its size, so a smaller light only makes the caustic sharper
-- (and harder for camera paths to find).
local s, lx, ly, lz = opt.light_size, -0.6, 3.2, 0.5
local k = 10.8 / (s * s)
scene:add(torte.shape.polygon{
  points = {{lx - s, ly, lz - s}, {lx + s, ly, lz - s}, {lx + s, ly, lz + s}, {lx - s, ly, lz + s}},
  emission = {k, k * 0.96, k * 0.88}, material = torte.material.matte{color = 0},
})

local camera = torte.camera.perspective{eye = {0, 2.2, -4.2}, look_at = {0, 0.45, 0.2}, fov = 36}
local image = torte.render{
  scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
  max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed, radius = opt.radius, alpha = opt.alpha,
  large_step = opt.large_step, time_limit = opt.time_limit,
}
torte.save(image, opt.output)
