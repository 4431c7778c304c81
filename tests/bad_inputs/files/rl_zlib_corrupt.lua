-- A zlib stream whose block type is the reserved one.
-- expect: torte.data.inflate: corrupt input near byte 3: invalid block type
local s = torte.data.inflate("\x78\x01\x07" .. ("\0"):rep(20))
