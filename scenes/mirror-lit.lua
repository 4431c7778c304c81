-- A room lit only off a mirror, in the spirit of Veach's test scenes (1997): a small lamp sits at the bottom of
-- an open-topped shaft and shines straight up at a mirror on the ceiling, which throws its light onto the floor;
-- everything the camera sees is lit by that patch of floor (light -> mirror -> floor -> ... -> eye). Camera paths
-- reach the lamp only by bouncing into the mirror and then hitting the small lamp by chance, and next-event
-- estimation cannot see it at all; `bdpt` starts paths at the lamp, which the mirror sends to the floor, and
-- connects them to the camera's.
--
--   torte scenes/mirror-lit.lua [width=400] [height=300] [spp=64] [max_depth=16]
--                               [integrator=path|direct|igi|lt|bdpt|vcm|ppm|mlt] [radius=0.01] [alpha=0.75] [large_step=0.3]
--                               [lamp_size=0.05] [time_limit=0] [output=out/mirror-lit.exr]
local torte = require "torte"

local opt = torte.options{
  width = 400, height = 300, spp = 64, max_depth = 16, integrator = "path", seed = 0,
  radius = 0.01, alpha = 0.75, large_step = 0.3, lamp_size = 0.05, time_limit = 0, output = "out/mirror-lit.exr",
}

local T, S, R = torte.translate, torte.scale, torte.rotate
local scene = torte.scene()
local white = torte.material.matte{color = {0.75, 0.75, 0.75}}

-- The room, x in [-3, 3], y in [0, 3], z in [-3, 3], seen from inside.
local function quad(points, material) scene:add(torte.shape.polygon{points = points, material = material}) end
quad({{-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}}, white)    -- floor
quad({{-3, 3, -3}, {3, 3, -3}, {3, 3, 3}, {-3, 3, 3}}, white)    -- ceiling
quad({{-3, 0, 3}, {-3, 3, 3}, {3, 3, 3}, {3, 0, 3}}, torte.material.matte{color = {0.75, 0.6, 0.4}})  -- back
quad({{-3, 0, -3}, {3, 0, -3}, {3, 3, -3}, {-3, 3, -3}}, white)  -- behind the camera
quad({{-3, 0, -3}, {-3, 3, -3}, {-3, 3, 3}, {-3, 0, 3}}, torte.material.matte{color = {0.3, 0.45, 0.7}})
quad({{3, 0, -3}, {3, 0, 3}, {3, 3, 3}, {3, 3, -3}}, torte.material.matte{color = {0.7, 0.35, 0.3}})

-- The mirror: a 2.4 x 2.4 panel just under the ceiling above the lamp.
local lx, lz = 1.2, 1.2
scene:add(torte.shape.cube{transform = T(lx, 2.97, lz) * S(1.2, 0.02, 1.2),
                           material = torte.material.mirror{color = {0.95, 0.95, 0.95}}})
-- The lamp: a small square facing up (+y) at the bottom of a shaft 0.8 high, open at the top, standing on a
-- pedestal; the shaft's walls keep its light off everything but the mirror.
local ly, s = 1.0, opt.lamp_size
local k = 12 / (s * s)  -- the lamp's power does not depend on its size
quad({{lx - s, ly, lz - s}, {lx - s, ly, lz + s}, {lx + s, ly, lz + s}, {lx + s, ly, lz - s}},
     torte.material.matte{color = 0})
scene:add(torte.shape.polygon{
  points = {{lx - s, ly + 0.001, lz - s}, {lx - s, ly + 0.001, lz + s}, {lx + s, ly + 0.001, lz + s},
            {lx + s, ly + 0.001, lz - s}},
  emission = {k, k * 0.93, k * 0.8}, material = torte.material.matte{color = 0},
})
local shaft = torte.material.matte{color = {0.2, 0.2, 0.2}}
local h, wsz = 0.4, 0.2  -- the shaft's half height and half width
for _, o in ipairs{{wsz, 0}, {-wsz, 0}, {0, wsz}, {0, -wsz}} do
  local sx, sz = o[1] == 0 and wsz or 0.01, o[2] == 0 and wsz or 0.01
  scene:add(torte.shape.cube{transform = T(lx + o[1], ly - 0.05 + h, lz + o[2]) * S(sx, h + 0.05, sz), material = shaft})
end
scene:add(torte.shape.cube{transform = T(lx, ly / 2, lz) * S(wsz, ly / 2, wsz), material = shaft})
-- Things on the floor for the light to fall on.
scene:add(torte.shape.sphere{radius = 0.5, transform = T(-1.0, 0.5, 0.6),
                             material = torte.material.plastic{color = {0.6, 0.2, 0.15}, roughness = 0.25}})
scene:add(torte.shape.cube{transform = T(0.2, 0.45, -0.8) * R(25, {0, 1, 0}) * S(0.45, 0.45, 0.45), material = white})

local camera = torte.camera.perspective{eye = {-0.5, 1.6, -2.9}, look_at = {0.3, 1.0, 1.0}, fov = 70}
local image = torte.render{
  scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
  max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed, radius = opt.radius, alpha = opt.alpha,
  large_step = opt.large_step, time_limit = opt.time_limit,
}
torte.save(image, opt.output)
