-- A Minecraft world lit by its own emitters: the bluenbt world's ancient city, at y = -48 to -42 (over 100 blocks
-- below sea level), with its rows of candles, soul fire and soul lanterns and a lava fall beside it (21,326 emitting
-- blocks in the world, 20,938 of them lava, most at this depth). Sun and sky hardly reach it, so the
-- light sampler has to find the emitters near each shading point among thousands of lava faces further away:
-- the many-emitter Minecraft view of docs/lights-and-sampling.md (scenes/minecraft.lua's default view is sunlit).
--
--   torte [--exposure 3] scenes/minecraft-cave.lua [camera=40,-38,30,18,-44,48] [fov=60]
--                                                  [every argument of minecraft.lua]
--
-- Lit by candles and lava alone the city is dark at exposure 0: --exposure 3 brightens the PNG preview.
-- Needs ../shared/data/minecraft/bluenbt-1.20.1-paper (see ../shared/data/SOURCES.md): without it minecraft.lua
-- renders the empty sky, with its notice unless --quiet (scripts/light-sampler-rmse.sh skips the scene then).
local torte = require "torte"
-- Looking west along the city's candle rows, the lava fall at the left edge.
torte.args.camera = torte.args.camera or "40,-38,30,18,-44,48"
torte.args.fov = torte.args.fov or 60
torte.args.output = torte.args.output or "out/minecraft-cave.exr"
-- minecraft.lua's errors (an unknown argument, say) name this script too, the one the user ran.
local ok, err = pcall(dofile, torte.script_dir .. "/minecraft.lua")
if not ok then error(tostring(err) .. " (in minecraft.lua, run by minecraft-cave.lua)", 0) end
