-- torte.data.read_file on a FIFO without a writer: refused at once.
-- expect: torte.data.read_file: cannot open 'rl_fifo' (it is a FIFO (named pipe), not a regular file)
-- timeout: 20
os.execute("mkfifo rl_fifo")
local s = torte.data.read_file("rl_fifo")
