-- A region file of 5000 bytes: shorter than its 8 KiB header.
-- expect: truncated region file: 5000 bytes, the header alone is 8192
-- where: r\.0\.0\.mca: truncated
-- args: lib=$CASE/mc_region.lib
local W = dofile(torte.args.lib)
W.write("r.0.0.mca", ("\0"):rep(5000))
require("minecraft.world").load{dir = "."}
