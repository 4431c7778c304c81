-- expect: --max-memory: 'lots' is not a memory size
-- flags: --max-memory lots
-- where: --max-memory
-- A command-line error: the script never runs.
error('the script ran')
