-- expect: cannot read image texture 'zero-width.tga' (0x8, 3 channels): the header declares no pixels
-- A TGA whose header says 0 pixels wide opened as a texture, and the first lookup divided by the width inside
-- OpenImageIO (SIGFPE); found by fuzz/fuzz_image.cc.
local header = string.pack("<BBBI2I2BI2I2I2I2BB", 0, 0, 2, 0, 0, 0, 0, 0, 0, 8, 24, 0)
local f = assert(io.open("zero-width.tga", "wb"))
f:write(header .. ("\128"):rep(64))
f:close()
local tex = torte.texture.image{file = "zero-width.tga"}
local scene = torte.scene()
scene:add(torte.shape.sphere{material = torte.material.matte{color = tex}})
scene:add(torte.light.point{position = {0, 0, -3}, intensity = 10})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -3}, look_at = {0, 0, 0}},
             width = 4, height = 4, spp = 1}
