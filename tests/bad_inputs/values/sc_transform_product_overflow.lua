-- expect: the product of the two transforms is not finite (it overflows float)
local _ = torte.scale(1e30) * torte.scale(1e30)
