-- expect: (/etc/passwd) may not be read under --sandbox
-- flags: --sandbox
-- ".." out of the script's own (readable) directory is resolved before the check.
local dir = debug.getinfo(1, "S").source:match("^@(.*)/")
io.open(dir .. "/../../../../../../../../../../etc/passwd")
