-- An environment map that is a directory.
-- expect: torte.light.environment: cannot read image 'rl_sky.exr': it is a directory, not a regular file
os.execute("mkdir rl_sky.exr")
local l = torte.light.environment{file = "rl_sky.exr"}
