-- expect: io.open: 'x.txt'
-- flags: --sandbox
-- Only ./out, --allow-write and the directory of output= are writable.
io.open("x.txt", "w")
