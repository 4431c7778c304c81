-- expect: may not be written under --sandbox
-- flags: --sandbox
-- The script's own directory is readable, not writable.
local dir = debug.getinfo(1, "S").source:match("^@(.*)/")
io.open(dir .. "/rt_append_script_dir.lua", "a")
