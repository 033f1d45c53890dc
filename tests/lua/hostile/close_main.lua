-- A to-be-closed value in the main chunk whose __close loops, closed by the budget error.
-- expect: instruction budget exhausted
-- args: --budget 2000000
local guard <close> = setmetatable({}, { __close = function() while true do end end })
while true do end
