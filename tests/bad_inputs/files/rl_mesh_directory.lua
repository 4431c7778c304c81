-- A directory named like a mesh, given as a shape's file.
-- expect: torte.shape.mesh: cannot open 'rl_dir.obj' (it is a directory, not a regular file)
os.execute("mkdir rl_dir.obj")
local s = torte.shape.mesh{file = "rl_dir.obj"}
