-- expect: --spp expects an integer in [1, 2147483647], got '3000000000'
-- flags: --spp 3000000000
-- where: --spp
-- A command-line error: the script never runs.
error('the script ran')
