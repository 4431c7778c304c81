-- `torte model.gltf|model.glb [key=value ...]`: renders a glTF file directly, as pbrt renders a .pbrt file. The
-- runtime calls the function this module returns with the model's absolute path instead of running a script.
--
--   camera=1          the file's camera to use (1-based, in file order); 0, or a file without cameras, frames
--                     the model from the front (+z, glTF's forward), a little above, with fov degrees vertical
--   fov=40            the framing camera's field of view
--   sky=auto          a default light rig (a uniform environment of radiance 0.25 and a sun-like directional light
--                     of irradiance 2, both times sky_strength) besides the file's lights and emissive materials:
--                     auto adds it when the file has no light, on always, off never
--   sky_strength=1
--   width=960 height=540 spp=64 integrator=path max_depth=16 seed=0
--   output=out/<model>.exr   (a PNG preview is written beside an EXR)
local torte = require "torte"

local function framing_camera(scene, fov, aspect)
  local b = scene:stats().bounds
  local lo, hi = b.min, b.max
  if not (lo[1] <= hi[1]) then error("the model holds no geometry to frame", 0) end
  local c = {(lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2, (lo[3] + hi[3]) / 2}
  local r = 0.5 * math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
  r = math.max(r, 1e-6)
  -- The bounding sphere fits the narrower of the two fields of view.
  local half = math.rad(fov) / 2
  local narrow = math.min(half, math.atan(math.tan(half) * aspect))
  local d = r / math.sin(narrow) * 1.05
  local dir = {0, 0.25, 1}
  local n = math.sqrt(dir[1] ^ 2 + dir[2] ^ 2 + dir[3] ^ 2)
  local eye = {c[1] + d * dir[1] / n, c[2] + d * dir[2] / n, c[3] + d * dir[3] / n}
  return torte.camera.perspective{eye = eye, look_at = c, fov = fov}
end

return function(path)
  local stem = path:match("([^/\\]+)%.[^.]*$") or "model"
  local opt = torte.options{
    camera = 1, fov = 40, sky = "auto", sky_strength = 1, width = 960, height = 540, spp = 64, integrator = "path",
    max_depth = 16, seed = 0, output = "out/" .. stem .. ".exr",
  }
  if opt.sky ~= "auto" and opt.sky ~= "on" and opt.sky ~= "off" then
    error(("argument 'sky' must be auto, on or off, got '%s'"):format(opt.sky), 0)
  end
  local g = torte.gltf.load(path)
  local scene = torte.scene()
  scene:add(torte.instance{group = g.group})  -- meshes under their node transforms, punctual lights
  for _, e in ipairs(g.emitters) do scene:add(e) end  -- emissive primitives (area lights cannot be instanced)
  local has_light = #g.lights > 0 or #g.emitters > 0
  if opt.sky == "on" or (opt.sky == "auto" and not has_light) then
    scene:add(torte.light.infinite{radiance = 0.25 * opt.sky_strength})
    scene:add(torte.light.directional{direction = {-0.4, -1, -0.6}, irradiance = 2 * opt.sky_strength})
  end
  local camera
  if opt.camera ~= 0 and g.cameras[opt.camera] then
    camera = g.cameras[opt.camera]
  elseif opt.camera ~= 0 and opt.camera ~= 1 then
    error(("argument 'camera' is %d but %s has %d camera%s"):format(opt.camera, path, #g.cameras,
                                                                    #g.cameras == 1 and "" or "s"), 0)
  else
    camera = framing_camera(scene, opt.fov, opt.width / opt.height)
  end
  local image = torte.render{scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp,
                             integrator = opt.integrator, max_depth = opt.max_depth, seed = opt.seed}
  torte.save(image, opt.output)
end
