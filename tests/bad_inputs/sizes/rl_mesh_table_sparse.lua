-- A positions table whose length is a border at 2^40 (41 entries): a clear error, not an 8 TB reservation.
-- expect: torte.shape.mesh: 'positions' entry 3 is not a number
local p = {}
for k = 0, 40 do p[1 << k] = 0 end
local s = torte.shape.mesh{positions = p, indices = {0, 1, 2}}
