-- expect: stack overflow
-- An __index function that indexes again: the recursion goes through C.
local t = setmetatable({}, {__index = function(self, key) return self[key .. "x"] end})
print(t.a)
