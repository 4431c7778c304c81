-- expect: (error object is a table value)
coroutine.wrap(function() error({}) end)()
