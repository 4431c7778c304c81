-- expect: torte.camera.perspective: 'transform' cannot be combined with eye/look_at/up
local _ = torte.camera.perspective{transform = torte.translate(0, 0, -5), up = {0, 1, 0}}
