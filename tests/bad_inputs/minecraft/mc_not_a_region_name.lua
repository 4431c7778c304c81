-- An explicit file list naming a file that is not r.X.Z.mca.
-- expect: not a region file name (expected r.<X>.<Z>.mca)
-- where: region\.dat: not a region
-- args: lib=$CASE/mc_region.lib
local W = dofile(torte.args.lib)
W.region("region.dat", {{0, 0, W.chunk(0, 0)}})
require("minecraft.world").load{files = {"region.dat"}}
