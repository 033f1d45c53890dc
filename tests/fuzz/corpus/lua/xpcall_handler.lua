-- xpcall whose message handler loops: the handler gets no time once the budget is gone.
-- expect: instruction budget exhausted
-- args: 
local function spin() while true do end end
local function handler(e) while true do end end
while true do xpcall(spin, handler) end
