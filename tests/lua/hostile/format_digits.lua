-- string.format("%.99f", 1e308) writes 408 digits in C, some 9 us: charged per byte it
-- makes (uncharged, 100 000 calls ran 0.8 s for about a million units).
-- expect: instruction budget exhausted
-- args: --budget 20000000
local s
for i = 1, 100000 do s = string.format("%.99f", 1e308) end
print(#s)
