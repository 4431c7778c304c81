-- expect: attempt to call a nil value (field 'getenv')
-- flags: --sandbox
print(os.getenv("HOME"))
