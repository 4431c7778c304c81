-- expect: scene:add: arrays nest more than 16 levels deep
local t = {torte.shape.sphere{}}
for _ = 1, 100 do t = {t} end
torte.scene():add(t)
