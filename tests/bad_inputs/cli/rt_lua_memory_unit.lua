-- expect: --lua-memory: '3Q' is not a memory size
-- flags: --lua-memory 3Q
-- where: --lua-memory
-- A command-line error: the script never runs.
error('the script ran')
