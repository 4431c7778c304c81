-- The light types side by side, on a floor. With light=mixed (the default), under a uniform blue sky (an
-- infinite light):
--   * image right: a ONE-SIDED emissive panel. It faces away from the camera, so we see its dark back; its light
--     falls only on the floor behind it.
--   * image left: the same panel made two_sided: it glows towards the camera as well and lights the floor on
--     both sides.
--   * centre: a warm point light above a white sphere, casting a hard shadow (the sky's shadows are soft).
-- Both panels are black matte (albedo 0), so whatever light comes from them is their own emission.
-- Other `light=` choices replace the sky and the point light (the panels stay):
--   spot         a spot light (cone 28 degrees, falloff from 20) aimed at the sphere, plus a dim sky
--   directional  a distant light (parallel rays, irradiance 2.5), plus a dim sky
--   environment  an equirectangular environment map, generated at run time into lights-env.exr beside `output` (bands of
--                colour with a bright "sun" patch) by rendering emissive strips with an orthographic camera
--   sky          the procedural Preetham sky with a sun (sun_elevation, sun_azimuth, turbidity)
--   all          every light at once
-- `aperture` > 0 renders through a thin lens focused on the sphere (focus_distance = the distance to look_at).
--
--   torte scenes/lights.lua [width=400] [height=300] [spp=32] [max_depth=8] [integrator=path|direct|lt]
--                           [camera=perspective|orthographic] [output=out/lights.exr]
--                           [light=mixed|spot|directional|environment|sky|all] [aperture=0]
--                           [sun_elevation=35] [sun_azimuth=-40] [turbidity=3]
local torte = require "torte"

local opt = torte.options{
  width = 400, height = 300, spp = 32, max_depth = 8, integrator = "path",
  camera = "perspective", output = "out/lights.exr", seed = 0,
  light = "mixed", aperture = 0, sun_elevation = 35, sun_azimuth = -40, turbidity = 3,
}
local valid = {mixed = true, spot = true, directional = true, environment = true, sky = true, all = true}
if not valid[opt.light] then
  error(("argument 'light' must be mixed, spot, directional, environment, sky or all, got \"%s\""):format(opt.light))
end
local function want(kind) return opt.light == kind or opt.light == "all" end

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

-- Sky: light of one colour from every direction (dimmer behind the spot and directional lights).
if opt.light == "mixed" then
  scene:add(torte.light.infinite{radiance = {0.20, 0.28, 0.42}})
elseif opt.light == "spot" or opt.light == "directional" then
  scene:add(torte.light.infinite{radiance = {0.04, 0.05, 0.08}})
end

if want("spot") then
  scene:add(torte.light.spot{position = {-1.5, 4, -1.5}, look_at = {0, 0.5, 0.3}, intensity = {40, 36, 30},
                             angle = 28, falloff = 20})
end
if want("directional") then
  scene:add(torte.light.directional{direction = {0.4, -1, 0.6}, irradiance = {2.5, 2.3, 2.0}})
end
if want("environment") then
  -- An equirectangular map made now: the image's columns are longitude, its rows latitude (top = up), so
  -- horizontal strips of emission become bands of sky; a small bright square is a low sun.
  local env_scene = torte.scene()
  local function strip(y0, y1, color)
    env_scene:add(torte.shape.polygon{points = {{-1, y0, 0}, {1, y0, 0}, {1, y1, 0}, {-1, y1, 0}},
                                     emission = color, two_sided = true})
  end
  strip(0.0, 0.5, {0.35, 0.55, 0.9})    -- upper sky, blue
  strip(-0.1, 0.0, {0.9, 0.8, 0.6})     -- horizon glow
  strip(-0.5, -0.1, {0.25, 0.2, 0.15})  -- ground, brown
  env_scene:add(torte.shape.polygon{points = {{0.3, 0.12, -0.01}, {0.36, 0.12, -0.01}, {0.36, 0.18, -0.01},
                                              {0.3, 0.18, -0.01}}, emission = {60, 54, 45}, two_sided = true})
  local env = torte.render{scene = env_scene, width = 128, height = 64, spp = 4, max_depth = 0,
                           camera = torte.camera.orthographic{eye = {0, 0, -1}, look_at = {0, 0, 0},
                                                              extent = 1, fov_axis = "vertical"}}
  local env_file = (opt.output:match("^(.*)/[^/]*$") or ".") .. "/lights-env.exr"
  torte.save(env, env_file)
  scene:add(torte.light.environment{file = env_file, transform = torte.rotate(-60, {0, 1, 0}), scale = 1})
end
if want("sky") then
  scene:add(torte.light.sky{sun_elevation = opt.sun_elevation, sun_azimuth = opt.sun_azimuth,
                            turbidity = opt.turbidity})
end

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
if opt.light == "mixed" or opt.light == "all" then
  scene:add(torte.light.point{position = {1.4, 2.8, -0.9}, intensity = {14, 9, 4}})
end

local camera
if opt.camera == "perspective" then
  camera = torte.camera.perspective{eye = {0, 3.4, -8}, look_at = {0, 0.8, 0.6}, fov = 35,
                                    aperture = opt.aperture}
elseif opt.camera == "orthographic" then
  -- Parallel projection from the same direction; `extent` is the image height in scene units.
  camera = torte.camera.orthographic{eye = {0, 3.4, -8}, look_at = {0, 0.8, 0.6}, extent = 5.6,
                                     aperture = opt.aperture}
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
