-- expect: -
-- sigint: 3
-- timeout: 20
-- flags: --sandbox
-- A render stopped by Ctrl-C returns its partial image; the script saves it (out/ is writable) and the run
-- still ends with 130.
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1})
scene:add(torte.light.infinite{radiance = 1})
local img = torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -4}},
                         width = 64, height = 64, spp = 16777216}
assert(img.interrupted, "the render was stopped by Ctrl-C")
torte.save(img, "out/partial.exr")
assert(io.open("out/partial.png"), "the PNG preview was written")
