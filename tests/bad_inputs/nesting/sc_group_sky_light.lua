-- expect: torte.light.sky at
-- where: sc_group_sky_light\.lua:[0-9]+: torte\.render: torte\.light\.sky at .*sc_group_sky_light\.lua:5 is in a group placed by an instance; sky lights cannot be instanced
-- Lights at infinity cannot be placed by an instance: the error names the light and where it was made.
local g = torte.group()
g:add(torte.light.sky{})
local scene = torte.scene()
scene:add(torte.shape.sphere{}, torte.instance{group = g, transform = torte.rotate(30, {0, 1, 0})})
torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -5}}, width = 4, height = 4, spp = 1}
