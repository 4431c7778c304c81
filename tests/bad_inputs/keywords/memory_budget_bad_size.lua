-- expect: torte.scene: 'memory_budget' must be a size such as "1.5GB"
local scene = torte.scene{memory_budget = "1.5 parsecs"}
scene:add(torte.shape.sphere{radius = 1})
