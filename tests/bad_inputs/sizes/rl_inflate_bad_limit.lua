-- A negative output limit for inflate.
-- expect: torte.data.inflate: the output limit must be a non-negative integer (bytes), got -1
local s = torte.data.inflate("\x78\x9c\x03\x00\x00\x00\x00\x01", -1)
