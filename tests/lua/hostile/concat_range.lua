-- table.concat over i..j = 0..2^63-1 of a table whose __index makes every element: charged
-- per element before the call (units past any budget, counted without overflow).
-- expect: instruction budget exhausted
-- args: --budget 5000000
local t = setmetatable({}, { __index = function(_, k) return "x" end })
print(#table.concat(t, "", 0, math.maxinteger))
