-- expect: os.remove: 'not-here.txt'
-- flags: --sandbox
os.remove("not-here.txt")
