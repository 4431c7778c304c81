-- expect: --lua-instructions expects an integer in [0, 9223372036854775807]
-- flags: --lua-instructions -1
-- where: --lua-instructions
-- A command-line error: the script never runs.
error('the script ran')
