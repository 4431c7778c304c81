-- expect: grid:save: 'grid.bin'
-- flags: --sandbox
torte.voxel.grid{}:save("grid.bin")
