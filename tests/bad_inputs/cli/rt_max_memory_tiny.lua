-- expect: --max-memory expects a size of at least 1.0 MB, got '10k'
-- flags: --max-memory 10k
-- where: --max-memory
-- A command-line error: the script never runs.
error('the script ran')
