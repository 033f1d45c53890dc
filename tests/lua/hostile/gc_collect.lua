-- collectgarbage("collect") walks the whole heap in C, some 9 ms for 300 000 small tables:
-- charged by the heap's size (uncharged, 200 collections ran 1.3 s for some 2 million units).
-- expect: instruction budget exhausted
-- args: --budget 20000000
local t = {}
for i = 1, 300000 do t[i] = { i } end
for k = 1, 200 do collectgarbage("collect") end
print(#t)
