-- expect: attempt to call a nil value (field 'getregistry')
local registry = debug.getregistry()
