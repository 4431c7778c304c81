-- Traversal speed on a scanned mesh, scalar against SIMD in one binary: torte.bench times the single-ray and
-- packet kernels on camera, diffuse and shadow rays on every SIMD target this CPU runs, and checks every
-- result against the scalar reference (a "no" in the last column is a wrong kernel, whatever its speed).
--
--   torte scenes/bench-traversal.lua [mesh=bunny|dragon|lucy|buddha|<.ply/.obj>] [grow=0] [width=512]
--                                    [height=512] [reps=5] [threads=1] [rays=camera,diffuse,shadow]
--                                    [kernels=single,packet8,packet16] [targets=all]
--
-- grow=N subdivides the mesh N times (x4 triangles each): bunny grow=4 is 17.8 M triangles, lucy grow=4 25.6 M.
-- The scene is the mesh on a floor inside a closed box under a square area light, as bench/workloads.h builds
-- it, so secondary rays always end on something. Prints Mrays/s (median of reps) per target and the speed-up of
-- the best target over scalar.
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
  rays = "camera,diffuse,shadow", kernels = "single,packet8,packet16", targets = "all",
}

local function split(s)
  local out = {}
  for word in s:gmatch("[^,%s]+") do out[#out + 1] = word end
  return out
end

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

local targets = {}
for _, name in ipairs(torte.simd.targets()) do  -- best first; printed from scalar up
  if opt.targets == "all" or opt.targets:find(name, 1, true) then table.insert(targets, 1, name) end
end

local stats = scene:stats()
print(("%s: %d triangles, %.1f bytes/triangle of acceleration, %dx%d rays, %d thread%s, median of %d"):format(
  opt.mesh, stats.triangles, stats.accel_bytes / stats.triangles, opt.width, opt.height, opt.threads,
  opt.threads == 1 and "" or "s", opt.reps))
local header = ("%-8s %-9s"):format("rays", "kernel")
for _, t in ipairs(targets) do header = header .. ("%10s"):format(t) end
print(header .. "   best/scalar  valid")
for _, rays in ipairs(split(opt.rays)) do
  for _, kernel in ipairs(split(opt.kernels)) do
    local line, rates, valid = ("%-8s %-9s"):format(rays, kernel), {}, true
    for _, t in ipairs(targets) do
      local r = torte.bench{scene = scene, camera = camera, rays = rays, kernel = kernel, simd = t,
                            width = opt.width, height = opt.height, reps = opt.reps, threads = opt.threads}
      rates[t] = r.mrays
      valid = valid and r.valid
      line = line .. ("%10.2f"):format(r.mrays)
    end
    local best = 0
    for _, v in pairs(rates) do best = math.max(best, v) end
    local ratio = rates.scalar and ("%11.2fx"):format(best / rates.scalar) or ("%12s"):format("-")
    print(line .. "  " .. ratio .. "  " .. (valid and "yes" or "NO"))
    io.stdout:flush()
  end
end
