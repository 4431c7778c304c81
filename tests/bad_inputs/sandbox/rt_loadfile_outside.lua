-- expect: loadfile: '/etc/passwd' may not be read
-- flags: --sandbox
loadfile("/etc/passwd")
