-- expect: io.open: '/etc/passwd' may not be read under --sandbox
-- flags: --sandbox
local f = io.open("/etc/passwd")
