-- Two Stanford dragons (100 k triangles each, the file's normals) on a matte floor under a uniform sky and one
-- area light: the mesh-heavy scene of `make bench-cycles` (bench/cycles/dragon.py builds the same in Cycles).
-- The materials are the ones both renderers have exactly: the left dragon a "plastic" blend of 90 % Lambert and
-- 10 % GGX gloss (an F = 1 conductor at roughness 0.3), the right one a GGX conductor with F ~ 1 at roughness 0.3.
--
--   torte scenes/dragon-bench.lua [width=256] [height=256] [spp=64] [max_depth=64] [data=<meshes directory>]
--                                 [output=out/dragon-bench.exr]
local torte = require "torte"

local script_dir = torte.script_dir  -- absolute: the paths below do not depend on the working directory
local opt = torte.options{
  width = 256, height = 256, spp = 64, max_depth = 64, seed = 0,
  data = script_dir .. "/../../shared/data/meshes", output = "out/dragon-bench.exr",
}
local T, S = torte.translate, torte.scale
local M = torte.material

-- eta = 1, k = 100: reflectance 0.9996 at normal incidence and above it at every angle, so the conductor is the
-- plain microfacet lobe Cycles' Glossy BSDF computes (which has no Fresnel term).
local gloss = M.metal{eta = {1, 1, 1}, k = {100, 100, 100}, roughness = 0.3}
local plastic = M.mix{a = M.matte{color = {0.7, 0.25, 0.08}}, b = gloss, amount = 0.1}
local floor = M.matte{color = {0.5, 0.5, 0.5}}

local scene = torte.scene()
local dragon = torte.mesh.load(opt.data .. "/dragon/dragon_100k_binary_le.ply")
local lo, hi = dragon:bounds()
-- About one unit wide, standing on y = 0, centred on the origin; Cycles applies the same numbers to the vertices.
local s = 1 / math.max(hi[1] - lo[1], hi[3] - lo[3])
local to_origin = S(s) * T(-(lo[1] + hi[1]) / 2, -lo[2], -(lo[3] + hi[3]) / 2)
scene:add(torte.shape.mesh{mesh = dragon, material = plastic, transform = T(0.6, 0, 0) * to_origin})
scene:add(torte.shape.mesh{mesh = dragon, material = gloss, transform = T(-0.6, 0, 0) * to_origin})
scene:add(torte.shape.mesh{positions = {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}},
                           indices = {0, 1, 2, 0, 2, 3}, material = floor})
-- A 1 x 1 area light 3 units up, emitting downwards only (its winding gives the normal -y).
scene:add(torte.shape.mesh{positions = {{-0.5, 3, -1}, {0.5, 3, -1}, {0.5, 3, 0}, {-0.5, 3, 0}},
                           indices = {0, 1, 2, 0, 2, 3}, material = M.matte{color = 0}, emission = {12, 11, 10}})
scene:add(torte.light.infinite{radiance = {0.30, 0.35, 0.45}})

local camera = torte.camera.perspective{eye = {0, 0.9, -2.5}, look_at = {0, 0.3, 0}, up = {0, 1, 0}, fov = 32}
local image = torte.render{
  scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
  max_depth = opt.max_depth, integrator = "path", seed = opt.seed, filter = torte.filter.box{radius = 0.5},
}
torte.save(image, opt.output)
