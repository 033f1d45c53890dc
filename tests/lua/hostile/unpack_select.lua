-- table.unpack pushes, and select walks, 200 000 values in C per call: charged per value.
-- expect: instruction budget exhausted
-- args: --budget 2000000
local t = {}
for i = 1, 200000 do t[i] = i end
local n = 0
for k = 1, 500 do n = n + select("#", table.unpack(t)) end
print(n)
