-- Writing a file: there is no io.
-- expect: attempt to index a nil value (global 'io')
local canary = ...
local f = io.open(canary, "w")
f:write("overwritten")
f:close()
