-- expect: --seed expects an integer in [0, 9223372036854775807], got '-1'
-- flags: --seed -1
-- where: --seed
-- A command-line error: the script never runs.
error('the script ran')
