-- expect: box filter radius must be a positive number
local _ = torte.filter.box{radius = 1e39}
