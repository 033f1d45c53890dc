-- Arithmetic on a 1 MiB string of digits converts the whole string in C each time (the
-- string metatable's __add): charged by the bytes converted, and so is tonumber.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local s = string.rep("0", 1 << 20)
local n = 0
for i = 1, 400 do n = n + (s + 0) + tonumber(s) end
print(n)
