-- A Minecraft world lit by its own emitters: the bluenbt world's ancient city, 45 blocks below sea level, with its
-- rows of candles, soul fire and soul lanterns and a lava fall beside it (21,326 emitting blocks in the world,
-- 20,938 of them lava, most at this depth). The sky and sun reach it only through the cave openings, so the
-- light sampler has to find the few hundred emitters near each shading point among thousands of lava faces:
-- the many-emitter Minecraft view of docs/lights-and-sampling.md (scenes/minecraft.lua's default view is sunlit).
--
--   torte scenes/minecraft-cave.lua [camera=40,-38,30,18,-44,48] [fov=60] [every argument of minecraft.lua]
--
-- Needs ../shared/data/minecraft/bluenbt-1.20.1-paper (see ../shared/data/SOURCES.md): without it the scene says
-- so and renders nothing.
local torte = require "torte"
local world = torte.args.world or torte.script_dir .. "/../../shared/data/minecraft/bluenbt-1.20.1-paper"
local found = false
for _, name in ipairs(torte.data.list_dir(world) or {}) do found = found or name:match("^r%.%-?%d+%.%-?%d+%.mca$") ~= nil end
if not found then
  io.stderr:write(("minecraft-cave.lua: skipped: world '%s' not found (../shared/data absent?)\n"):format(world))
  return
end
-- Looking west along the city's candle rows, the lava fall at the left edge.
torte.args.camera = torte.args.camera or "40,-38,30,18,-44,48"
torte.args.fov = torte.args.fov or 60
torte.args.output = torte.args.output or "out/minecraft-cave.exr"
return dofile(torte.script_dir .. "/minecraft.lua")
