-- A script that fails on rank 1 only, after rank 0 has entered the render: the job must end with a non-zero
-- exit and one line naming the rank and its message (tests/distributed/run.sh failing-rank).
local torte = require "torte"
if torte.rank == 1 then error("rank one refuses to render") end
local script_dir = torte.script_dir
local scene, camera = dofile(script_dir .. "/../../scenes/lib/cornell-box.lua")(torte)
torte.save(torte.render{scene = scene, camera = camera, width = 64, height = 64, spp = 64}, "out/never.exr")
