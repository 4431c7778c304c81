-- The Cornell box, exactly as specified in ../shared/scenes/cornell-box-spec.md (measured data from the
-- Cornell Program of Computer Graphics). Units are millimetres; +x points to the image's left.
--
--   torte scenes/cornell-box.lua [width=512] [height=512] [spp=256] [max_depth=64]
--                                [integrator=path|direct|igi|lt|bdpt|vcm|ppm|mlt] [output=out/cornell-box.exr]
--                                [vpl_sets=4] [light_paths=64] [g_limit=20] [vpl_roulette=0.25]   (igi only)
--                                [radius=0.01] [alpha=0.75]   (vcm and ppm only)
--                                [large_step=0.3] [chains=0]   (mlt only)
local torte = require "torte"

local opt = torte.options{
  width = 512, height = 512, spp = 256, max_depth = 64, integrator = "path",
  output = "out/cornell-box.exr", seed = 0,
  -- instant global illumination (integrator=igi); the defaults of torte.render
  vpl_sets = 4, light_paths = 64, g_limit = 20, vpl_roulette = 0.25,
  -- vertex connection and merging, progressive photon mapping (integrator=vcm|ppm)
  radius = 0.01, alpha = 0.75,
  -- Metropolis light transport (integrator=mlt)
  large_step = 0.3, chains = 0,
}

local script_dir = torte.script_dir  -- absolute: the paths below do not depend on the working directory
local scene, camera = dofile(script_dir .. "/lib/cornell-box.lua")(torte)

local image = torte.render{
  scene = scene, camera = camera,
  width = opt.width, height = opt.height, spp = opt.spp, max_depth = opt.max_depth,
  integrator = opt.integrator, seed = opt.seed,
  vpl_sets = opt.vpl_sets, light_paths = opt.light_paths, g_limit = opt.g_limit, vpl_roulette = opt.vpl_roulette,
  radius = opt.radius, alpha = opt.alpha, large_step = opt.large_step, chains = opt.chains,
  filter = torte.filter.box{radius = 0.5},
}
torte.save(image, opt.output)
