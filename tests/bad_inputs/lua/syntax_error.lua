-- expect: unexpected symbol
local x = = 1
