-- A missing key looked up through 1 990 __index tables: the VM follows the chain inside one
-- instruction (24 us, one unit), so the budget would let the loop below run for days.  The
-- host's time limit per call into the script stops it.
-- expect: time limit exceeded
-- args: --timeout 1
local t = {}
for i = 1, 1990 do t = setmetatable({}, { __index = t }) end
local n = 0
for k = 1, 100000000 do if t.missing then n = n + 1 end end
print(n)
