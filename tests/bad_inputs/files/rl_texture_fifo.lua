-- A FIFO named like an image: refused at once (opening it would wait for a writer).
-- expect: cannot open image texture 'rl_fifo.png': it is a FIFO (named pipe), not a regular file
-- timeout: 20
os.execute("mkfifo rl_fifo.png")
local t = torte.texture.image{file = "rl_fifo.png"}
