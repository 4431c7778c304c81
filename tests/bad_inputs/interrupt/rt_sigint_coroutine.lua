-- expect: -
-- sigint: 3
-- timeout: 10
coroutine.wrap(function() while true do end end)()
