-- table.insert shifting #t = 2^62 elements, #t from a __len metamethod.
-- expect: instruction budget exhausted
-- args: --budget 2000000
local t = setmetatable({}, { __len = function() return math.maxinteger // 2 end })
table.insert(t, 1, "x")
