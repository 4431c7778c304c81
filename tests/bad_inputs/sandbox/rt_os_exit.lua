-- expect: attempt to call a nil value (field 'exit')
-- flags: --sandbox
os.exit(0)
