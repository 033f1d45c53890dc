-- table.concat appends each element in C, and formats each number: charged per element, so
-- concatenating a table of 100 000 empty strings 1 000 times is stopped (uncharged, the
-- calls run 1.6 s for some 0.5 million units: the result is short, nothing is allocated).
-- expect: instruction budget exhausted
-- args: --budget 20000000
local t = {}
for i = 1, 100000 do t[i] = "" end
local n = 0
for k = 1, 1000 do n = n + #table.concat(t) end
print(n)
