-- An NBT list of ints declaring 2^31 - 1 entries in 16 bytes.
-- expect: torte.data.nbt: truncated input: list of 2147483647 entries needs
local s = torte.data.nbt("\x09\x00\x01L\x03\x7f\xff\xff\xff" .. ("\0"):rep(16))
