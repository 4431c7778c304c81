-- expect: --threads expects an integer in [1, 4096], got '4294967296'
-- flags: --threads 4294967296
-- where: --threads
-- A command-line error: the script never runs.
error('the script ran')
