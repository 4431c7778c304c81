-- A voxel far outside the grid's coordinate range.
-- expect: voxel grid: chunk (16777216, 0, 0) is out of range
local g = torte.voxel.grid{}
g:set(1 << 28, 0, 0, 1)
