-- Two rooms joined by a door left ajar, after Veach's test scenes (1997, Fig. 10.3): the lamp is in the far
-- room, the camera in the near one, and every bit of light the camera sees came through the gap after at least
-- two bounces. Camera paths must find the gap by chance and then the lamp by chance again; `bdpt` starts paths
-- at the lamp, which carry the light through the gap for the camera paths to connect to.
--
--   torte scenes/door-gap.lua [width=400] [height=300] [spp=64] [max_depth=16]
--                             [integrator=path|direct|igi|lt|bdpt|vcm|ppm|mlt] [radius=0.01] [alpha=0.75] [large_step=0.3]
--                             [gap=0.3] [time_limit=0] [output=out/door-gap.exr]
local torte = require "torte"

local opt = torte.options{
  width = 400, height = 300, spp = 64, max_depth = 16, integrator = "path", seed = 0,
  radius = 0.01, alpha = 0.75, large_step = 0.3, gap = 0.3, time_limit = 0, output = "out/door-gap.exr",
}

local T, S, R = torte.translate, torte.scale, torte.rotate
local scene = torte.scene()
local white = torte.material.matte{color = {0.75, 0.75, 0.75}}
local warm = torte.material.matte{color = {0.75, 0.55, 0.35}}
local blue = torte.material.matte{color = {0.3, 0.4, 0.7}}

-- One long box, x in [-4, 4], y in [0, 3], z in [-3, 3], seen from inside; the near room is z < 0.
local function quad(points, material) scene:add(torte.shape.polygon{points = points, material = material}) end
quad({{-4, 0, -3}, {-4, 0, 3}, {4, 0, 3}, {4, 0, -3}}, white)    -- floor, normal +y
quad({{-4, 3, -3}, {4, 3, -3}, {4, 3, 3}, {-4, 3, 3}}, white)    -- ceiling, normal -y
quad({{-4, 0, 3}, {-4, 3, 3}, {4, 3, 3}, {4, 0, 3}}, warm)       -- far room's back wall
quad({{-4, 0, -3}, {4, 0, -3}, {4, 3, -3}, {-4, 3, -3}}, white)  -- near room's back wall (behind the camera)
quad({{-4, 0, -3}, {-4, 3, -3}, {-4, 3, 3}, {-4, 0, 3}}, blue)   -- the -x wall
quad({{4, 0, -3}, {4, 0, 3}, {4, 3, 3}, {4, 3, -3}}, white)      -- the +x wall

-- The dividing wall at z = 0 with a doorway x in [0.5, 1.5], y in [0, 2.2]; the door, hinged at x = 1.5,
-- turned so only a narrow gap at x = 0.5 lets light through.
local wall = torte.material.matte{color = {0.7, 0.7, 0.7}}
scene:add(torte.shape.cube{transform = T(-1.75, 1.5, 0) * S(2.25, 1.5, 0.05), material = wall})
scene:add(torte.shape.cube{transform = T(2.75, 1.5, 0) * S(1.25, 1.5, 0.05), material = wall})
scene:add(torte.shape.cube{transform = T(1, 2.6, 0) * S(0.5, 0.4, 0.05), material = wall})
local open = math.deg(math.asin(math.min(1, opt.gap)))
scene:add(torte.shape.cube{transform = T(1.5, 1.1, 0) * R(-open, {0, 1, 0}) * T(-0.5, 0, 0) * S(0.5, 1.1, 0.03),
                           material = white})

-- The lamp: a small panel low in the far room, facing the far wall (normal +z), so even the far room is lit
-- indirectly.
scene:add(torte.shape.polygon{
  points = {{-1.2, 0.8, 1.2}, {-0.7, 0.8, 1.2}, {-0.7, 1.3, 1.2}, {-1.2, 1.3, 1.2}},
  emission = {900, 820, 700}, material = torte.material.matte{color = 0},
})
-- Something in the near room for the light to fall on.
scene:add(torte.shape.sphere{radius = 0.45, transform = T(-1.2, 0.45, -1.4),
                             material = torte.material.plastic{color = {0.6, 0.2, 0.15}, roughness = 0.25}})
scene:add(torte.shape.cube{transform = T(2.2, 0.4, -1.6) * R(20, {0, 1, 0}) * S(0.4, 0.4, 0.4), material = white})

local camera = torte.camera.perspective{eye = {-3.4, 1.8, -2.85}, look_at = {0.5, 0.6, -0.3}, fov = 72}
local image = torte.render{
  scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
  max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed, radius = opt.radius, alpha = opt.alpha,
  large_step = opt.large_step, time_limit = opt.time_limit,
}
torte.save(image, opt.output)
