-- expect: an emitting shape in a group placed by an instance; area lights cannot be instanced
-- where: sc_group_emitter\.lua:[0-9]+: torte\.render: torte\.shape\.disk at .*sc_group_emitter\.lua:5:
-- Emitting shapes in instanced groups are refused by name (lights such as point lights are placed).
local g = torte.group()
g:add(torte.shape.disk{emission = {1, 1, 1}})
local scene = torte.scene()
scene:add(torte.shape.sphere{}, torte.instance{group = g})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
