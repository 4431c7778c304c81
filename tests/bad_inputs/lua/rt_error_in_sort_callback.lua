-- expect: comparison refused
-- An error without a location from a Lua function that table.sort (C) calls.
table.sort({3, 1, 2}, function(a, b) error("comparison refused", 0) end)
