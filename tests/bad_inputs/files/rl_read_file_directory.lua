-- torte.data.read_file on a directory (it returned "").
-- expect: torte.data.read_file: cannot open '.' (it is a directory, not a regular file)
local s = torte.data.read_file(".")
