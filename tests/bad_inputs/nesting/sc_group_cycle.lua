-- expect: scene:add: the instance's group already places this group (a group cannot contain itself)
-- Two groups holding instances of each other: refused when the cycle is made (shared owners in a cycle would
-- never be freed), not unrolled forever at torte.render.
local a, b = torte.group(), torte.group()
a:add(torte.shape.sphere{})
a:add(torte.instance{group = b, transform = torte.translate(1, 0, 0)})
b:add(torte.instance{group = a, transform = torte.translate(0, 1, 0)})
local scene = torte.scene()
scene:add(torte.instance{group = a})
scene:add(torte.light.point{position = {0, 5, 0}})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
