-- table.sort without a comparator runs its n log n comparisons in C: charged as many units.
-- expect: instruction budget exhausted
-- args: --budget 5000000
local t = {}
for i = 1, 1000000 do t[i] = i end
for k = 1, 3 do table.sort(t) end
print(#t)
