-- The scalar-vs-SIMD table of scenes/bench-traversal.lua and scenes/bench-minecraft.lua, for any scene and
-- camera: torte.bench on every ray kind x kernel x SIMD target (and Embree, when torte has it), Mrays/s (median
-- of opt.reps), the best target's speed-up over scalar and over Embree, and whether every kernel agreed with
-- the scalar reference. opt: width, height, reps, threads, rays, kernels, targets (comma lists), embree.
--   dofile(torte.script_dir .. "/lib/bench-table.lua")(torte, scene, camera, opt, label)
return function(torte, scene, camera, opt, label)
  local function split(s)
    local out = {}
    for word in s:gmatch("[^,%s]+") do out[#out + 1] = word end
    return out
  end
  local targets = {}
  for _, name in ipairs(torte.simd.targets()) do  -- best first; printed from scalar up
    if opt.targets == "all" or opt.targets:find(name, 1, true) then table.insert(targets, 1, name) end
  end

  -- Does this torte have the Embree kernel? One tiny call tells (it also builds the Embree scene, kept for later).
  local embree = false
  if opt.embree then
    local ok, err = pcall(torte.bench, {scene = scene, camera = camera, kernel = "embree", width = 16, height = 16,
                                        reps = 1})
    embree = ok
    if not ok and not tostring(err):find("without Embree", 1, true) then
      print("embree column left out: " .. tostring(err))
    end
  end

  local stats = scene:stats()
  local what = {}
  if stats.triangles > 0 then
    local b = stats.bytes_per_triangle  -- the triangle BVH's own: nodes, leaf vertices, index map
    what[#what + 1] = ("%d triangles, %.1f bytes/triangle of acceleration"):format(stats.triangles,
                                                                                 b.nodes + b.leaves + b.index_map)
  end
  if stats.voxels > 0 then
    what[#what + 1] = ("%d voxels, %.2f bytes/voxel"):format(stats.voxels, stats.voxel_bytes_per_voxel)
  end
  if stats.instances > 0 then what[#what + 1] = ("%d instances"):format(stats.instances) end
  print(("%s: %s; %dx%d rays, %d thread%s, median of %d"):format(label, table.concat(what, ", "), opt.width,
    opt.height, opt.threads, opt.threads == 1 and "" or "s", opt.reps))
  local header = ("%-8s %-9s"):format("rays", "kernel")
  for _, t in ipairs(targets) do header = header .. ("%10s"):format(t) end
  if embree then header = header .. ("%10s"):format("embree") end
  print(header .. "   best/scalar" .. (embree and "  best/embree" or "") .. "  valid")
  for _, rays in ipairs(split(opt.rays)) do
    local e  -- Embree on these rays, the same for every kernel row
    if embree then
      e = torte.bench{scene = scene, camera = camera, rays = rays, kernel = "embree", width = opt.width,
                      height = opt.height, reps = opt.reps, threads = opt.threads}
    end
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
      if e then
        line = line .. ("%10.2f"):format(e.mrays)
        ratio = ratio .. ("%12.2fx"):format(best / e.mrays)
        valid = valid and e.valid
      end
      print(line .. "  " .. ratio .. "  " .. (valid and "yes" or "NO"))
      io.stdout:flush()
    end
  end
end
