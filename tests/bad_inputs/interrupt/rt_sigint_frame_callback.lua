-- expect: -
-- sigint: 3
-- timeout: 10
-- Lua code called back from C++ (scene:frame).
torte.scene():frame(function(group) while true do end end)
