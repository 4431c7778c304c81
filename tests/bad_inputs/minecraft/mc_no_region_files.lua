-- A world folder without region files: the error is at the script line that loads it.
-- expect: no region files (r.X.Z.mca) in '.' or its region/ folder
local f = assert(io.open("level.txt", "w"))
f:write("not a world")
f:close()
require("minecraft.world").load{dir = "."}
