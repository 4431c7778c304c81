-- expect: os.rename: 'moved.txt'
-- flags: --sandbox
-- Renaming removes the old name and creates the new one: both must be writable.
os.rename("out/a.txt", "moved.txt")
