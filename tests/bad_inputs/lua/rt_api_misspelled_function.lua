-- expect: torte.material has no 'plastik' (known: bump, glass, lambert, mask, matte, metal, mirror, mix, plastic, rough_glass)
-- A misspelled API function is named at its line with the names that exist, instead of "attempt to call a nil
-- value (field 'plastik')".
local sphere = torte.shape.sphere{material = torte.material.plastik{color = 0.5}}
