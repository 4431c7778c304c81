-- Traversal speed on a scanned mesh, scalar against SIMD in one binary: torte.bench times the single-ray and
-- packet kernels on camera, diffuse and shadow rays on every SIMD target this CPU runs, and checks every
-- result against the scalar reference (a "no" in the last column is a wrong kernel, whatever its speed).
--
--   torte scenes/bench-traversal.lua [mesh=bunny|dragon|lucy|buddha|<.ply/.obj>] [grow=0] [width=512]
--                                    [height=512] [reps=5] [threads=1] [rays=camera,diffuse,shadow]
--                                    [kernels=single,packet8,packet16] [targets=all] [embree=true]
--
-- grow=N subdivides the mesh N times (x4 triangles each): bunny grow=4 is 17.8 M triangles, lucy grow=4 25.6 M.
-- The scene is the mesh on a floor inside a closed box under a square area light, as bench/workloads.h builds
-- it, so secondary rays always end on something. Prints Mrays/s (median of reps) per target and the speed-up of
-- the best target over scalar. When torte is built with Embree (probed once: torte.bench{kernel = "embree"}), an
-- `embree` column gives Embree's Mrays/s on the same rays (one measurement per ray kind: rtcIntersect16 for camera
-- rays, rtcOccluded16 for shadow rays, rtcIntersect1 for diffuse rays, as embree-compare pairs them) and
-- best/embree the best target of the row's kernel against it; embree=false leaves it out.
local torte = require "torte"

local data = torte.script_dir .. "/../../shared/data/meshes"
local known = {
  bunny = data .. "/bunny/bun_zipper.ply",
  dragon = data .. "/dragon/dragon_100k_binary_le.ply",
  lucy = data .. "/lucy/lucy_100k.obj",
  buddha = data .. "/happy-buddha/happy_vrip_res3.ply",
}
local opt = torte.options{
  mesh = "bunny", grow = 0, width = 512, height = 512, reps = 5, threads = 1,
  rays = "camera,diffuse,shadow", kernels = "single,packet8,packet16", targets = "all", embree = true,
}

local path = known[opt.mesh] or opt.mesh
local file = io.open(path, "rb")
if not file then
  print(("bench-traversal: %s is missing (../shared/data holds the Stanford meshes); nothing to measure"):format(path))
  return
end
file:close()

local mesh = torte.mesh.load(path)
if opt.grow > 0 then mesh = mesh:subdivide{levels = opt.grow} end
mesh:fit{height = 1, center = {0, 0, 0}, floor = true}

local scene = torte.scene()
local grey = torte.material.matte{color = 0.5}
scene:add(torte.shape.mesh{mesh = mesh, material = grey})
-- A closed box around the model (2.4 wide, 1.6 high) and an area light just below its ceiling.
scene:add(torte.shape.cube{transform = torte.translate(0, 0.8, 0) * torte.scale(1.2, 0.8, 1.2), material = grey})
scene:add(torte.shape.polygon{
  points = {{-0.3, 1.55, -0.3}, {0.3, 1.55, -0.3}, {0.3, 1.55, 0.3}, {-0.3, 1.55, 0.3}},
  emission = {10, 10, 10}, material = grey,
})
local camera = torte.camera.perspective{eye = {0, 0.55, 1.15}, look_at = {0, 0.45, 0}, fov = 50}

dofile(torte.script_dir .. "/lib/bench-table.lua")(torte, scene, camera, opt, opt.mesh)
