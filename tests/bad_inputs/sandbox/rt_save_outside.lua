-- expect: image:write: 'elsewhere/x.exr'
-- flags: --sandbox
local img = torte.render{scene = torte.scene(), camera = torte.camera.perspective{}, width = 2, height = 2, spp = 1}
torte.save(img, "elsewhere/x.exr")
