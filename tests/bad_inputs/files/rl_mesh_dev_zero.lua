-- A mesh that is a symlink to /dev/zero: refused, not read until memory runs out.
-- expect: torte.mesh.load: cannot open 'rl_zero.ply' (it is a character device, not a regular file)
os.execute("ln -s /dev/zero rl_zero.ply")
local m = torte.mesh.load("rl_zero.ply")
