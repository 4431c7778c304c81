-- expect: --spp expects an integer in [1, 2147483647], got '4294967297'
-- flags: --spp 4294967297
-- where: --spp
-- A command-line error: the script never runs.
error('the script ran')
