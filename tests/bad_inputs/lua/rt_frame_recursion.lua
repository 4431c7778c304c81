-- expect: C stack overflow
-- A scene:frame callback that recurses: the overflow happens in C (no Lua line of its own).
local scene = torte.scene()
local function fill(group) group:frame(fill) end
fill(scene)
