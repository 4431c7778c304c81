-- expect: scene:add: arrays nest more than 16 levels deep (does an array contain itself?)
-- An array that contains itself recursed without end (and nested arrays overflowed the Lua stack at ~50 levels).
local t = {torte.shape.sphere{}}
t[2] = t
torte.scene():add(t)
