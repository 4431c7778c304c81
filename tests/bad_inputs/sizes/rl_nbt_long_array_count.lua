-- An NBT long array declaring 2^31 - 1 entries.
-- expect: torte.data.nbt: truncated input: long array of 2147483647 entries needs
local s = torte.data.nbt("\x0a\x00\x00\x0c\x00\x01A\x7f\xff\xff\xff" .. ("\0"):rep(64))
