-- An error value that is not a string, with a __tostring that never returns.
-- expect: (error object is a table value)
-- args: --budget 2000000
error(setmetatable({}, { __tostring = function() while true do end end }))
