-- expect: debug.setmetatable: the metatable of a userdata (torte.shape) cannot be changed
local scene, shape = torte.scene(), torte.shape.sphere{}
debug.setmetatable(shape, debug.getmetatable(scene))
