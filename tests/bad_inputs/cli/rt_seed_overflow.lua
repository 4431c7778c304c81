-- expect: --seed expects an integer in [0, 9223372036854775807]
-- flags: --seed 99999999999999999999
-- where: --seed
-- A command-line error: the script never runs.
error('the script ran')
