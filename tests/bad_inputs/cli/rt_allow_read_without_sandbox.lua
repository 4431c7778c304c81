-- expect: --allow-read and --allow-write only apply with --sandbox
-- flags: --allow-read /tmp
-- where: --sandbox
-- A command-line error: the script never runs.
error('the script ran')
