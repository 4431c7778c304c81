-- expect: attempt to call a nil value
local t = {}
t.missing()
