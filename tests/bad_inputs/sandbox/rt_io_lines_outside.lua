-- expect: io.lines: '/etc/passwd' may not be read
-- flags: --sandbox
for line in io.lines("/etc/passwd") do end
