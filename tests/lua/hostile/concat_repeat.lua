-- table.concat appends each element in C, and formats each number: charged per element, so
-- concatenating one table of 100 000 strings 1 000 times is stopped (the allocations alone
-- would charge some 1.6 million units).
-- expect: instruction budget exhausted
-- args: --budget 20000000
local t = {}
for i = 1, 100000 do t[i] = "x" end
local n = 0
for k = 1, 1000 do n = n + #table.concat(t) end
print(n)
