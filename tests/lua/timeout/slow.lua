-- 40 000 lookups through 1 990 __index tables: some 0.4-0.8 s, for some 160 000 units (each
-- lookup one instruction).  tests/lua/run.lua runs it under a time limit it passes and with
-- the limit off.
local t = {}
for i = 1, 1990 do t = setmetatable({}, { __index = t }) end
local n = 0
for k = 1, 40000 do if t.missing == nil then n = n + 1 end end
print("lookups " .. n)
