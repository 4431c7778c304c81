-- A zlib (type 2) chunk whose bytes are not a zlib stream.
-- expect: torte.data.inflate: corrupt input
-- where: r\.0\.0\.mca: chunk \(0, 0\) \(entry 0,0 of the region\)
-- args: lib=$CASE/mc_region.lib
local W = dofile(torte.args.lib)
W.region("r.0.0.mca", {{0, 0, ("\x78\x9c") .. ("\255"):rep(200), compression = 2}})
require("minecraft.world").load{dir = "."}
