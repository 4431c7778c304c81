-- expect: attempt to call a nil value (field 'execute')
-- flags: --sandbox
os.execute("true")
