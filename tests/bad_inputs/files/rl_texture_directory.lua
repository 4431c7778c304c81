-- A directory named like an image.
-- expect: cannot open image texture 'rl_dir.png': it is a directory, not a regular file
os.execute("mkdir rl_dir.png")
local t = torte.texture.image{file = "rl_dir.png"}
