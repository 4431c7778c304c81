-- Traversal speed in a Minecraft world, scalar against SIMD in one binary: scenes/minecraft.lua with bench=true,
-- which builds the world's voxel grid (and the sea around it) and times torte.bench's kernels on camera, diffuse
-- and shadow rays from the scene's camera on every SIMD target this CPU runs (scenes/lib/bench-table.lua).
--
--   torte scenes/bench-minecraft.lua [world=...] [box=...] [camera=...] [width=960] [height=540] [reps=5]
--                                    [threads=1] [rays=camera,diffuse,shadow] [kernels=single,packet8,packet16]
--                                    [targets=all]
--
-- Every argument of scenes/minecraft.lua applies (the world, its box and camera).
local torte = require "torte"
torte.args.bench = true
return dofile(torte.script_dir .. "/minecraft.lua")
