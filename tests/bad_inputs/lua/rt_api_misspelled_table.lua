-- expect: torte has no 'materials' (known:
-- A misspelled table of the API, one level up.
local m = torte.materials.matte{}
