-- torte.data.read_file on a symlink to /dev/zero: the target is checked.
-- expect: torte.data.read_file: cannot open 'rl_zero.mca' (it is a character device, not a regular file)
os.execute("ln -s /dev/zero rl_zero.mca")
local s = torte.data.read_file("rl_zero.mca")
