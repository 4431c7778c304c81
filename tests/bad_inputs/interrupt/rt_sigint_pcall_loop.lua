-- expect: -
-- sigint: 3
-- timeout: 10
while true do pcall(function() while true do end end) end
