-- A texture read from /dev/zero through a symlink.
-- expect: cannot open image texture 'rl_zero.png': it is a character device, not a regular file
os.execute("ln -s /dev/zero rl_zero.png")
local t = torte.texture.image{file = "rl_zero.png"}
