-- expect: scene:add: this voxel grid's cells place the group it is added to (a group cannot contain itself)
-- A voxel grid whose cell shape is the group the grid is then added to: refused when the cycle is made.
local cell = torte.group()
cell:add(torte.shape.sphere{radius = 0.3, transform = torte.translate(0.5, 0.5, 0.5)})
local grid = torte.voxel.grid{}
grid:set(0, 0, 0, -3)
grid:define{id = -3, shape = cell}
cell:add(grid:shape{})
