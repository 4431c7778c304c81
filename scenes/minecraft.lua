-- A Minecraft Java world rendered from its region files: lua/minecraft/ reads the Anvil files (through the
-- generic torte.data bindings: files, zlib, NBT, bit fields), maps every block state to a 16-bit voxel id with a
-- procedural look (minecraft.blocks), and fills a torte.voxel.grid; a physical sky with a sun lights it.
--
--   torte scenes/minecraft.lua [world=<folder with r.X.Z.mca, or a world folder with region/>]
--                              [box=x0,y0,z0,x1,y1,z1] [camera=ex,ey,ez,lx,ly,lz] [fov=40]
--                              [sun_elevation=35] [sun_azimuth=-50] [emission=true] [skip_bad_chunks=false] [sea=true]
--                              [sea_radius=2e7]
--                              [width=960] [height=540] [spp=16] [max_depth=6] [integrator=path|direct|lt]
--                              [output=out/minecraft.exr] [seed=0]
--                              [bench=false] [reps=5] [threads=1] [rays=camera,diffuse,shadow]
--                              [kernels=single,packet8,packet16] [targets=all] [embree=true]
--
-- world: default ../shared/data/minecraft/bluenbt-1.20.1-paper (relative to this script); a bare name such as
--   world=prismarine-1.16 is looked up in that folder too. Every world there has framing defaults below.
-- box: block coordinates, x0 <= x < x1 (etc.); only those blocks are loaded. camera: eye and look-at in world
--   block coordinates; by default the camera frames the loaded terrain from the south-east, above the surface.
-- sea: water at sea level (a surface at y = 62.875) around the loaded blocks, out to sea_radius blocks: far enough
--   that no ray slips between its edge and the horizon (below which the sky is black; see docs/minecraft.md).
-- Blocks take their biome's tint (grass, leaves, vines, water) and fences, walls and panes join their neighbours.
-- emission: emitting blocks (torches, lanterns, glowstone, lava, fire, ...) light the scene: their faces and
--   flames are area lights of the voxel grid, sampled by power (docs/voxels.md). emission=false: unlit look only.
-- When the world folder is missing the scene renders the empty sky (with a notice unless --quiet).
-- bench=true (scenes/bench-minecraft.lua): instead of rendering, times the traversal kernels on this world's
--   voxel grid from the same camera at width x height (torte.bench; the table of scenes/lib/bench-table.lua).
local torte = require "torte"
local world = require "minecraft.world"
local blocks = require "minecraft.blocks"

local script_dir = torte.script_dir  -- absolute: the paths below do not depend on the working directory
local data_dir = script_dir .. "/../../shared/data/minecraft"

local opt = torte.options{
  world = data_dir .. "/bluenbt-1.20.1-paper", box = "", camera = "", fov = 40, sun_elevation = 35,
  sun_azimuth = -50, emission = true, skip_bad_chunks = false, sea = true, sea_radius = 2e7,
  width = 960, height = 540, spp = 16, max_depth = 6, integrator = "path", output = "out/minecraft.exr",
  seed = 0, bench = false, reps = 5, threads = 1, rays = "camera,diffuse,shadow", kernels = "single,packet8,packet16",
  targets = "all", embree = true,
}

local function numbers(s, n, name)
  local out = {}
  for v in tostring(s):gmatch("[^,%s]+") do
    local x = tonumber(v)
    if not x then error(("argument '%s': '%s' is not a number"):format(name, v), 2) end
    out[#out + 1] = x
  end
  if #out ~= n then error(("argument '%s' needs %d comma-separated numbers, got '%s'"):format(name, n, s), 2) end
  return out
end

-- Per-world framing: a box that keeps the interesting part and the view (azimuth/elevation of the camera seen
-- from the target, distance as a multiple of the box size). Keys are the folder names in shared data.
local WORLDS = {
  ["bluenbt-1.20.1-paper"] = {view = {az = 215, el = 22, dist = 0.8}},
  ["prismarine-1.8.9"] = {view = {az = 250, el = 22, dist = 0.75}},
  ["prismarine-1.12.2"] = {view = {az = 200, el = 22, dist = 0.6}},
  ["prismarine-1.14.4"] = {view = {az = 200, el = 22, dist = 0.7}},
  ["prismarine-1.16"] = {view = {az = 200, el = 22, dist = 0.7}},
  ["prismarine-1.21.1"] = {view = {az = 220, el = 22, dist = 1.2}},
  ["querz-nbt-1.18.2"] = {view = {az = 215, el = 22, dist = 0.8}},
  ["querz-nbt-1.18-21w44a-lushcave"] = {view = {az = 220, el = 15, dist = 3.5}},
  -- The debug worlds: a grid of every block at y = 70 (a few full chunk columns around it are left out).
  ["mcaselector-anvil112"] = {box = {0, 69, 0, 96, 84, 96}, view = {az = 200, el = 30, dist = 0.9}},
  ["mcaselector-anvil113"] = {box = {0, 69, 0, 96, 84, 96}, view = {az = 200, el = 30, dist = 0.9}},
}

local dir = opt.world
local function is_dir(d) return torte.data.list_dir(d) ~= nil end
if not is_dir(dir) and is_dir(data_dir .. "/" .. dir) then dir = data_dir .. "/" .. dir end
local name = dir:gsub("[/\\]+$", ""):match("([^/\\]+)$") or dir
local preset = WORLDS[name] or {}

local box = opt.box ~= "" and numbers(opt.box, 6, "box") or preset.box
local scene = torte.scene()
scene:add(torte.light.sky{sun_elevation = opt.sun_elevation, sun_azimuth = opt.sun_azimuth})

local eye, look_at
local have_world = is_dir(dir) and #world.region_files(dir) > 0
if have_world then
  local reg = blocks.registry()
  local grid = torte.voxel.grid{}
  -- Per section layer: how full it is, to find the terrain surface for the default camera.
  local layer_fill = {}
  local sections = {}
  local stats = world.load{
    dir = dir, box = box, registry = reg, skip_bad_chunks = opt.skip_bad_chunks, progress = not torte.quiet,
    sink = function(cx, cy, cz, ids, non_air)
      sections[cx .. "," .. cy .. "," .. cz] = ids
      layer_fill[cy] = (layer_fill[cy] or 0) + non_air
    end,
  }
  -- Only the top of each body of water is kept (one refraction per ray instead of one per block).
  local t_water = torte.clock()
  local deep_water, water_surface = world.water_surfaces(sections, reg:ids_of("minecraft:water"))
  t_water = torte.clock() - t_water
  -- In a fixed order (pairs() order changes from run to run, and so would the grid's chunk table).
  local keys = {}
  for key in pairs(sections) do
    local cx, cy, cz = key:match("^(%-?%d+),(%-?%d+),(%-?%d+)$")
    keys[#keys + 1] = {tonumber(cx), tonumber(cy), tonumber(cz), key}
  end
  table.sort(keys, function(a, b)
    if a[1] ~= b[1] then return a[1] < b[1] end
    if a[2] ~= b[2] then return a[2] < b[2] end
    return a[3] < b[3]
  end)
  for _, k in ipairs(keys) do grid:set_chunk(k[1], k[2], k[3], sections[k[4]]) end
  sections = nil
  reg:define(grid, {emission = opt.emission})
  if not torte.quiet then
    local dvs = {}
    for _, dv in ipairs(world.sorted_keys(stats.data_versions)) do
      dvs[#dvs + 1] = ("%d (%d chunks)"):format(dv, stats.data_versions[dv])
    end
    local unknown = {}
    for n, c in pairs(stats.unknown) do
      unknown[#unknown + 1] = ("%s %d"):format(world.printable(n):gsub("^minecraft:", ""), c)
    end
    table.sort(unknown)
    io.stderr:write(("minecraft: %s: %d chunks (%d full, %d not full, %d bad), DataVersion %s, %d sections, "
                     .. "%d non-air blocks, %d voxels in the grid (%d water cells below the surface left out), "
                     .. "loaded in %.2f s (+ %.2f s for water surfaces)\n"):format(
      name, stats.chunks, stats.full, stats.not_full, stats.bad, table.concat(dvs, ", "), stats.sections,
      stats.non_air, grid:count(), deep_water, stats.seconds, t_water))
    if #unknown > 0 then
      io.stderr:write(("minecraft: %d blocks of unknown kinds drawn magenta: %s\n"):format(stats.unknown_blocks,
                                                                                          table.concat(unknown, ", ")))
    end
  end
  scene:add(grid:shape{})

  -- The sea around the loaded blocks: four water quads framing them, out to 200 km (past the horizon).
  local b = stats.bounds
  if opt.sea and b.lo[1] < b.hi[1] then
    local x0, z0, x1, z1 = b.lo[1], b.lo[3], b.hi[1], b.hi[3]
    if box then x0, z0, x1, z1 = math.max(x0, box[1]), math.max(z0, box[3]), math.min(x1, box[4]), math.min(z1, box[6]) end
    local y, R = 62.875, 200000
    -- Tinted like the most common water surface of the loaded blocks (their biome's water colour).
    local wd, best = blocks.definition("water"), 0
    for _, id in ipairs(world.sorted_keys(water_surface)) do  -- ties: the lowest id
      local n = water_surface[id]
      if n > best and reg:tint(id) then wd, best = blocks.tinted_definition(blocks.definition("water"), reg:tint(id)), n end
    end
    local water = blocks.make_material(wd, wd.color)
    local function quad(ax, az, bx, bz)
      scene:add(torte.shape.polygon{points = {{ax, y, az}, {ax, y, bz}, {bx, y, bz}, {bx, y, az}}, material = water})
    end
    quad(-R, -R, R, z0)
    quad(-R, z1, R, R)
    quad(-R, z0, x0, z1)
    quad(x1, z0, R, z1)
    -- An outer ring out to R2: rays that pass beyond R still dip below the horizon, where the sky is black; seen
    -- from 100-200 blocks up, 200 km leaves a gap of about half a pixel at the horizon (a dark line). At R2 the gap
    -- is far below a pixel. (Separate quads: the near sea keeps the precision of the 200 km quads.)
    local R2 = opt.sea_radius
    if R2 > R then
      quad(-R2, -R2, R2, -R)
      quad(-R2, R, R2, R2)
      quad(-R2, -R, -R, R)
      quad(R, -R, R2, R)
    end
  end

  -- Default camera: look at the middle of the loaded blocks, at the height of the terrain surface.
  local b = stats.bounds
  if b.lo[1] < b.hi[1] then
    local lo, hi = {b.lo[1], b.lo[2], b.lo[3]}, {b.hi[1], b.hi[2], b.hi[3]}
    if box then
      for k = 1, 3 do lo[k], hi[k] = math.max(lo[k], box[k]), math.min(hi[k], box[k + 3]) end
    end
    local columns = (hi[1] - lo[1]) * (hi[3] - lo[3])
    local surface = lo[2]
    for cy = hi[2] // 16, lo[2] // 16, -1 do
      local f = (layer_fill[cy] or 0) / math.max(1, columns * 16)
      if f > 0.25 then surface = cy * 16 + math.floor(16 * math.min(f, 1)) break end
    end
    local centre = {(lo[1] + hi[1]) / 2, surface, (lo[3] + hi[3]) / 2}
    local size = math.max(hi[1] - lo[1], hi[3] - lo[3])
    local v = preset.view or {az = 215, el = 35, dist = 0.9}
    local az, el = math.rad(v.az), math.rad(v.el)
    local d = size * v.dist
    eye = {centre[1] + d * math.cos(el) * math.sin(az), centre[2] + d * math.sin(el),
           centre[3] + d * math.cos(el) * math.cos(az)}
    look_at = {centre[1], centre[2] + 0.3 * d * math.sin(el), centre[3]}  -- aim high enough to see the sky
  end
elseif not torte.quiet then
  io.stderr:write(("minecraft.lua: world '%s' not found (../shared/data absent?); rendering the empty sky\n"):format(
    opt.world))
end

if opt.camera ~= "" then
  local c = numbers(opt.camera, 6, "camera")
  eye, look_at = {c[1], c[2], c[3]}, {c[4], c[5], c[6]}
end
eye = eye or {0, 80, -60}
look_at = look_at or {0, 70, 0}

local camera = torte.camera.perspective{eye = eye, look_at = look_at, up = {0, 1, 0}, fov = opt.fov}
if opt.bench then
  if not have_world then error("bench=true needs a world (" .. dir .. " has no region files)", 0) end
  dofile(script_dir .. "/lib/bench-table.lua")(torte, scene, camera, opt, name)
  return
end
local image = torte.render{scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
                           max_depth = opt.max_depth, integrator = opt.integrator, seed = opt.seed}
torte.save(image, opt.output)
