-- A FIFO named like a mesh: refused at once instead of waiting for a writer.
-- expect: torte.mesh.load: cannot open 'rl_fifo.obj' (it is a FIFO (named pipe), not a regular file)
-- timeout: 20
os.execute("mkfifo rl_fifo.obj")
local m = torte.mesh.load("rl_fifo.obj")
