-- expect: torte.data.read_file: '/etc/passwd' may not be read
-- flags: --sandbox
torte.data.read_file("/etc/passwd")
