-- expect: [torte] torte.prelude
-- An error raised inside torte's embedded Lua: the script's line comes first.
local opt = torte.options(42)
