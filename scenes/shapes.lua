-- Every shape torte knows, each placed by a rotation and/or a non-uniform scale: sphere (squashed into an
-- ellipsoid), disk (with a hole), open cylinder, cube, planar polygon and a triangle mesh (a smooth torus built
-- here in Lua). Lit by a point light and a glowing sphere (an area light); matte materials throughout.
--
--   torte scenes/shapes.lua [width=400] [height=300] [spp=64] [max_depth=8]
--                           [integrator=path|direct|lt] [output=out/shapes.exr]
local torte = require "torte"

local opt = torte.options{
  width = 400, height = 300, spp = 64, max_depth = 8, integrator = "path",
  output = "out/shapes.exr", seed = 0,
}

local function matte(r, g, b) return torte.material.matte{color = {r, g, b}} end
local white = matte(0.75, 0.75, 0.72)
local red = matte(0.75, 0.12, 0.10)
local orange = matte(0.85, 0.45, 0.10)
local yellow = matte(0.80, 0.70, 0.15)
local green = matte(0.15, 0.55, 0.20)
local blue = matte(0.12, 0.30, 0.75)
local purple = matte(0.50, 0.18, 0.65)

local T, R, S = torte.translate, torte.rotate, torte.scale
local scene = torte.scene()

-- Floor and back wall: a square polygon and a thin slab (a cube scaled flat).
scene:add(torte.shape.polygon{
  points = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}},  -- wound so its normal is +y
  material = white,
})
scene:add(torte.shape.cube{transform = T(0, 4, 4.2) * S(10, 4, 0.1), material = white})

-- Back row ----------------------------------------------------------------------------------------------------
-- An open cylinder (its axis is z), lying on the floor with an open end turned towards the camera so its
-- inside shows; squashed a little into an elliptic tube.
scene:add(torte.shape.cylinder{
  radius = 0.6, z_min = -0.8, z_max = 0.8,
  transform = T(-2.6, 0.55, 1.7) * R(18, {0, 1, 0}) * S(1, 0.9, 1),
  material = green,
})
-- A cube stretched into a tall box, turned about y and leaning.
scene:add(torte.shape.cube{
  transform = T(0, 1.15, 2.0) * R(8, {0, 0, 1}) * R(30, {0, 1, 0}) * S(0.5, 1.1, 0.5),
  material = yellow,
})
-- A triangle mesh: a torus with per-vertex normals, standing on edge and turned towards the camera.
local function torus(major, minor, nu, nv)
  local positions, normals, uvs, indices = {}, {}, {}, {}
  for i = 0, nu - 1 do
    local u = 2 * math.pi * i / nu
    local cu, su = math.cos(u), math.sin(u)
    for j = 0, nv - 1 do
      local v = 2 * math.pi * j / nv
      local cv, sv = math.cos(v), math.sin(v)
      positions[#positions + 1] = {(major + minor * cv) * cu, minor * sv, (major + minor * cv) * su}
      normals[#normals + 1] = {cv * cu, sv, cv * su}
      uvs[#uvs + 1] = {i / nu, j / nv}
    end
  end
  local function index(i, j) return (i % nu) * nv + (j % nv) end
  for i = 0, nu - 1 do
    for j = 0, nv - 1 do
      local a, b, c, d = index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)
      for _, k in ipairs{a, c, b, a, d, c} do indices[#indices + 1] = k end
    end
  end
  return {positions = positions, normals = normals, uvs = uvs, indices = indices}
end
local ring = torus(0.75, 0.28, 64, 24)
ring.transform = T(2.5, 1.05, 1.6) * R(-30, {0, 1, 0}) * R(75, {1, 0, 0})
ring.material = orange
scene:add(torte.shape.mesh(ring))

-- Front row ---------------------------------------------------------------------------------------------------
-- A sphere squashed into an ellipsoid and tilted.
scene:add(torte.shape.sphere{
  radius = 1, transform = T(-2.1, 0.55, -1.1) * R(-25, {0, 0, 1}) * S(0.9, 0.55, 0.6),
  material = red,
})
-- A disk (an annulus: it has an inner radius), stretched into an ellipse and stood up, facing the camera.
scene:add(torte.shape.disk{
  radius = 0.7, inner_radius = 0.3,
  transform = T(0, 0.7, -1.2) * R(-25, {0, 1, 0}) * R(-10, {1, 0, 0}) * S(0.8, 1, 1),
  two_sided = true, material = blue,
})
-- A regular hexagon (a polygon), stood up and turned, sheared by a non-uniform scale.
local hexagon = {}
for k = 0, 5 do
  local a = math.pi / 3 * k
  hexagon[#hexagon + 1] = {math.cos(a), math.sin(a), 0}
end
scene:add(torte.shape.polygon{
  points = hexagon,
  transform = T(2.1, 0.75, -1.1) * R(30, {0, 1, 0}) * R(20, {0, 0, 1}) * S(0.75, 0.6, 1),
  material = purple,
})

-- Lights ------------------------------------------------------------------------------------------------------
-- A glowing sphere: an area light (emission) that is also seen directly.
scene:add(torte.shape.sphere{
  radius = 0.35, transform = T(-0.6, 2.9, 0.6),
  emission = {10, 7.5, 4.5}, material = torte.material.matte{color = 0},
})
-- A point light, up and in front (+x is the image's left, as in a right-handed frame looking along +z).
scene:add(torte.light.point{position = {-3, 5, -4}, intensity = {45, 45, 50}})

local camera = torte.camera.perspective{
  eye = {0, 3.0, -7.5}, look_at = {0, 0.9, 0.3}, up = {0, 1, 0}, fov = 38,
}

local image = torte.render{
  scene = scene, camera = camera,
  width = opt.width, height = opt.height, spp = opt.spp, max_depth = opt.max_depth,
  integrator = opt.integrator, seed = opt.seed,
}
torte.save(image, opt.output)
