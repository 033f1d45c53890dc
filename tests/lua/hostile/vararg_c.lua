-- math.max walks its arguments in C: a C function is charged the values it is passed, here
-- 200 000 forwarded from a vararg list, 2 000 times.
-- expect: instruction budget exhausted
-- args: --budget 20000000
local t = {}
for i = 1, 200000 do t[i] = i end
local function largest(...)
  local m = 0
  for k = 1, 2000 do m = math.max(m, ...) end
  return m
end
print(largest(table.unpack(t)))
