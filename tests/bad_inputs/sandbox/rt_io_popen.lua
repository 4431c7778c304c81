-- expect: attempt to call a nil value (field 'popen')
-- flags: --sandbox
io.popen("ls")
