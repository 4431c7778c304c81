-- expect: scene:frame: the frame's group places the scene or group it is framed in (a group cannot contain itself)
-- A frame whose filling function places the group the frame is made in: refused before the cycle exists.
local outer = torte.group()
outer:add(torte.shape.sphere{})
outer:frame(function(g) g:add(torte.instance{group = outer}) end)
