-- < between two long strings of different lengths reads their common prefix inside one
-- instruction: charged like ==, by what the shorter one may cost.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local a = string.rep("x", 1 << 20)
local b = string.rep("x", (1 << 19) + 100)
local n = 0
for i = 1, 20000 do
  if b < a then n = n + 1 end
end
print(n)
