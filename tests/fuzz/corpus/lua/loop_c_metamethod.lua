-- table.concat over a table whose __index is itself a C function: a loop with no
-- instruction to count; the call hook charges every call.
-- expect: instruction budget exhausted
-- args: 
local t = setmetatable({}, { __index = table.concat })
print(#table.concat(t, "", 1, math.maxinteger))
