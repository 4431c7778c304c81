-- warning
-- expect: torte.render: the scene is empty (no shapes, no lights): the image is black
torte.render{scene = torte.scene(), camera = torte.camera.perspective{}, width = 4, height = 4, spp = 1}
