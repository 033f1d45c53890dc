-- print writes out each string it is given: a 64 KiB string printed again and again is
-- charged by its size.
-- expect: instruction budget exhausted
-- args: --budget 200000
local s = string.rep("x", 1 << 16)
for i = 1, 100 do print(s) end
