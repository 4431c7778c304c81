-- expect: (error object is a table value whose __tostring failed)
error(setmetatable({}, {__tostring = function() error("cannot describe") end}))
