-- expect: attempt to call a nil value (field 'sethook')
-- flags: --sandbox
debug.sethook()
