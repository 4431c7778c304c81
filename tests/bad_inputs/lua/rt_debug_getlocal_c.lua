-- expect: debug.getlocal: the locals of C functions are not accessible
-- Level 2 is gsub, a C function with its string buffer on its stack.
("abc"):gsub(".", function() return debug.getlocal(2, 1) end)
