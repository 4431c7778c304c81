-- expect: dofile: '/etc/passwd' may not be read
-- flags: --sandbox
dofile("/etc/passwd")
