-- expect: setmetatable: __gc metamethods are not available under --sandbox
-- flags: --sandbox
-- Lua runs finalizers with hooks off: they would escape the instruction limit and Ctrl-C.
setmetatable({}, {__gc = function() while true do end end})
