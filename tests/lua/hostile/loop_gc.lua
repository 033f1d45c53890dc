-- A finalizer that never returns: Lua runs finalizers with hooks off, out of the budget's
-- reach, so the sandbox refuses __gc metamethods.
-- expect: __gc metamethods are not available in the sandbox
setmetatable({}, { __gc = function() while true do end end })
collectgarbage()
