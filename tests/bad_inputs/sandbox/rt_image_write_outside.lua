-- expect: may not be written under --sandbox
-- flags: --sandbox
local img = torte.render{scene = torte.scene(), camera = torte.camera.perspective{}, width = 2, height = 2, spp = 1}
img:write("/tmp/rt_image_write_outside.png")
