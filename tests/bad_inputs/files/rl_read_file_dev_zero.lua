-- torte.data.read_file on /dev/zero: refused (it read until memory ran out).
-- expect: torte.data.read_file: cannot open '/dev/zero' (it is a character device, not a regular file)
local s = torte.data.read_file("/dev/zero")
