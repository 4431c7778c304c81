-- expect: io.output: 'log.txt' (
-- flags: --sandbox
io.output("log.txt")
