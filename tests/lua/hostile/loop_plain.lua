-- An infinite loop: stopped by the instruction budget.
-- expect: instruction budget exhausted
-- args: --budget 2000000
local n = 0
while true do n = n + 1 end
