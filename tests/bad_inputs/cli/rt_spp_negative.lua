-- expect: --spp expects an integer in [1, 2147483647], got '-8'
-- flags: --spp -8
-- where: --spp
-- A command-line error: the script never runs.
error('the script ran')
