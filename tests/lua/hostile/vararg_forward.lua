-- f(...) copies the whole vararg list into the call in one instruction: a call is charged
-- the values it passes, to a Lua function (here 200 000 varargs, 2 000 times) as to C.
-- expect: instruction budget exhausted
-- args: --budget 20000000
local t = {}
for i = 1, 200000 do t[i] = i end
local function sink(...) end
local function forward(...)
  for k = 1, 2000 do sink(...) end
end
forward(table.unpack(t))
print("done")
