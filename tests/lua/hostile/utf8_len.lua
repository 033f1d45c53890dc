-- utf8.len scans its string in C: charged by the bytes it scans.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local s = string.rep("a", 1 << 20)
local n = 0
for i = 1, 1000 do n = n + utf8.len(s) end
print(n)
