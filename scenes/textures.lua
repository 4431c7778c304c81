-- Procedural and image textures: a checkered floor, marble (a colour spline over turbulence), a 3D checker cube,
-- wood-like rings, a bump-mapped sphere, a mix of two materials by a noise mask, and Keenan Crane's Spot cow
-- with its image texture (../shared/data/meshes/spot; skipped with a message when absent).
--
--   torte scenes/textures.lua [width=800] [height=450] [spp=64] [max_depth=8] [integrator=path|direct|lt]
--                             [data=<meshes directory>] [output=out/textures.exr]
local torte = require "torte"

local script_dir = torte.script_dir  -- absolute: the paths below do not depend on the working directory
local opt = torte.options{
  width = 800, height = 450, spp = 64, max_depth = 8, integrator = "path", seed = 0,
  data = script_dir .. "/../../shared/data/meshes", output = "out/textures.exr",
}

local T, S, R = torte.translate, torte.scale, torte.rotate
local X, M = torte.texture, torte.material
local scene = torte.scene()

-- Floor: a checkerboard in world xz (planar mapping), one unit per square.
local floor_tex = X.checker{a = {0.75, 0.73, 0.7}, b = {0.18, 0.18, 0.2}}
                  .. X.planar{s = {1, 0, 0}, t = {0, 0, 1}}
scene:add(torte.shape.polygon{points = {{-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}},
                              material = M.matte{color = floor_tex}})

-- Marble: turbulence through a spline of colours, in plastic.
local marble = X.spline{colors = {{0.9, 0.89, 0.86}, {0.85, 0.84, 0.8}, {0.2, 0.2, 0.24}, {0.88, 0.87, 0.84}},
                        positions = {0, 0.3, 0.45, 0.6}}
               .. X.turbulence{octaves = 6} .. X.xyz{transform = S(0.7, 0.7, 0.7)}
scene:add(torte.shape.sphere{radius = 0.6, transform = T(1.9, 0.6, 0.6),
                             material = M.plastic{color = marble, roughness = 0.15}})

-- A cube with a 3D checker: the pattern runs through the solid, so edges line up.
local cells = X.checker3d{a = {0.8, 0.25, 0.1}, b = {0.95, 0.85, 0.5}} .. X.xyz{transform = S(0.25, 0.25, 0.25)}
scene:add(torte.shape.cube{transform = T(0.55, 0.45, 1.3) * R(25, {0, 1, 0}) * S(0.45, 0.45, 0.45),
                           material = M.matte{color = cells}})

-- Wood-like grain: fBm stretched along the log's axis (y) through a spline of browns.
local rings = X.spline{colors = {{0.55, 0.33, 0.15}, {0.78, 0.52, 0.26}, {0.45, 0.26, 0.1}, {0.7, 0.45, 0.2}}}
              .. X.fbm{octaves = 4} .. X.xyz{transform = S(0.15, 2.5, 0.15)}
scene:add(torte.shape.cylinder{radius = 0.35, z_min = 0, z_max = 1.1, transform = T(-0.4, 0, 1.9) * R(-90, {1, 0, 0}),
                               material = M.matte{color = rings}})

-- Bump mapping: a copper sphere hammered by Perlin noise.
local dents = X.perlin{} .. X.xyz{transform = S(0.08, 0.08, 0.08)}
scene:add(torte.shape.sphere{radius = 0.45, transform = T(-1.3, 0.45, 0.9),
                             material = M.bump{material = M.metal{metal = "copper", roughness = 0.2},
                                               height = dents, scale = 0.02}})

-- A mix of gold and blue matte paint by a noise mask ("peeling paint").
local mask = X.fbm{octaves = 5} .. X.xyz{transform = S(0.25, 0.25, 0.25)}
scene:add(torte.shape.sphere{radius = 0.45, transform = T(-2.4, 0.45, 0.2),
                             material = M.mix{a = M.matte{color = {0.1, 0.25, 0.6}},
                                              b = M.metal{metal = "gold", roughness = 0.25},
                                              amount = mask}})

-- Spot, with its image texture on the mesh's uvs.
local spot_obj = opt.data .. "/spot/spot_triangulated.obj"
local file = io.open(spot_obj, "rb")
if file then
  file:close()
  local spot = torte.mesh.load(spot_obj)
  local lo, hi = spot:bounds()
  local s = 1.1 / (hi[2] - lo[2])
  scene:add(torte.shape.mesh{
    mesh = spot, transform = T(0.4, 0, -0.2) * R(140, {0, 1, 0}) * S(s) * T(-(lo[1] + hi[1]) / 2, -lo[2], -(lo[3] + hi[3]) / 2),
    material = M.matte{color = X.image{file = opt.data .. "/spot/spot_texture.png"}},
  })
else
  io.stderr:write(("textures.lua: %s not found (../shared/data absent?); no cow\n"):format(spot_obj))
end

-- Light: a warm rectangular area light and a cool sky.
scene:add(torte.shape.polygon{
  points = {{1.5, 4, -2.5}, {3.5, 4, -2.5}, {3.5, 4, -0.5}, {1.5, 4, -0.5}},
  emission = {9, 8.5, 7.5}, material = M.matte{color = 0},
})
scene:add(torte.light.infinite{radiance = {0.25, 0.3, 0.4}})

local camera = torte.camera.perspective{eye = {0, 2.2, -4.6}, look_at = {0, 0.45, 0.8}, fov = 36}
local image = torte.render{
  scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
  max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed,
}
torte.save(image, opt.output)
