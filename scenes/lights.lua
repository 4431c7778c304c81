-- The light types side by side, on a floor under a uniform blue sky (an infinite light):
--   * image right: a ONE-SIDED emissive panel. It faces away from the camera, so we see its dark back; its light
--     falls only on the floor behind it.
--   * image left: the same panel made two_sided: it glows towards the camera as well and lights the floor on
--     both sides.
--   * centre: a warm point light above a white sphere, casting a hard shadow (the sky's shadows are soft).
-- Both panels are black matte (albedo 0), so whatever light comes from them is their own emission.
--
--   torte scenes/lights.lua [width=400] [height=300] [spp=32] [max_depth=8] [integrator=path|direct]
--                           [camera=perspective|orthographic] [output=out/lights.exr]
local torte = require "torte"

local opt = torte.options{
  width = 400, height = 300, spp = 32, max_depth = 8, integrator = "path",
  camera = "perspective", output = "out/lights.exr", seed = 0,
}

local T, R, S = torte.translate, torte.rotate, torte.scale
local scene = torte.scene()

local floor_material = torte.material.matte{color = {0.7, 0.7, 0.68}}
local white = torte.material.matte{color = {0.8, 0.8, 0.8}}
local black = torte.material.matte{color = 0}

-- The floor: a big square facing +y.
scene:add(torte.shape.polygon{
  points = {{-30, 0, -30}, {-30, 0, 30}, {30, 0, 30}, {30, 0, -30}},
  material = floor_material,
})

-- Sky: light of one colour from every direction.
scene:add(torte.light.infinite{radiance = {0.20, 0.28, 0.42}})

-- Two emissive panels. In object space the panel is a 1.6 x 1 rectangle in the z = 0 plane whose front faces
-- +z (its points run counter-clockwise seen from +z): standing almost upright, it faces away from the camera and
-- a little down. +x is the image's left.
local function panel(x, two_sided)
  scene:add(torte.shape.polygon{
    points = {{-0.8, -0.5, 0}, {0.8, -0.5, 0}, {0.8, 0.5, 0}, {-0.8, 0.5, 0}},
    transform = T(x, 1.25, 0.6) * R(x > 0 and -15 or 15, {0, 1, 0}) * R(15, {1, 0, 0}),
    emission = {7, 5.6, 4}, two_sided = two_sided, material = black,
  })
  -- Something for each panel to light: a cube behind it, one in front of it.
  scene:add(torte.shape.cube{transform = T(x, 0.3, 1.9) * R(25, {0, 1, 0}) * S(0.3), material = white})
  scene:add(torte.shape.cube{transform = T(x, 0.3, -0.8) * R(-20, {0, 1, 0}) * S(0.3), material = white})
end
panel(2.3, true)     -- image left: two-sided
panel(-2.3, false)   -- image right: one-sided

-- Centre: a sphere under a warm point light.
scene:add(torte.shape.sphere{radius = 0.55, transform = T(0, 0.55, 0.3), material = white})
scene:add(torte.light.point{position = {1.4, 2.8, -0.9}, intensity = {14, 9, 4}})

local camera
if opt.camera == "perspective" then
  camera = torte.camera.perspective{eye = {0, 3.4, -8}, look_at = {0, 0.8, 0.6}, fov = 35}
elseif opt.camera == "orthographic" then
  -- Parallel projection from the same direction; `extent` is the image height in scene units.
  camera = torte.camera.orthographic{eye = {0, 3.4, -8}, look_at = {0, 0.8, 0.6}, extent = 5.6}
else
  error(("argument 'camera' must be \"perspective\" or \"orthographic\", got \"%s\""):format(opt.camera))
end

local image = torte.render{
  scene = scene, camera = camera,
  width = opt.width, height = opt.height, spp = opt.spp, max_depth = opt.max_depth,
  integrator = opt.integrator, seed = opt.seed,
  -- The sky's power grows with the scene's size, so picking one light by power would nearly always pick the
  -- sky and leave the small panels noisy: sample every light at every bounce instead.
  sample_all_lights = true,
}
torte.save(image, opt.output)
