-- next(t) from the start scans every empty slot before the first live one, inside one call:
-- here a million (0.4 ms) for a charge of one unit, so no budget stops the loop below in
-- under an hour.  The host's time limit per call into the script does.
-- expect: time limit exceeded
-- args: --timeout 1
local t = {}
for i = 1, 1000000 do t[i] = true end
for i = 1, 999999 do t[i] = nil end
local n = 0
for k = 1, 10000000 do if next(t) then n = n + 1 end end
print(n)
