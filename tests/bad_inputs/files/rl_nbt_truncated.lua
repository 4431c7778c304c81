-- An NBT compound cut inside a string.
-- expect: torte.data.nbt: truncated input: a string needs 100 bytes, 5 left in 'root.name'
local s = torte.data.nbt("\x0a\x00\x04root" .. "\x08\x00\x04name" .. "\x00\x64hello")
