-- A coroutine.wrap body that loops, holding a to-be-closed value whose __close loops too:
-- after the budget kills the coroutine, its __close must not run without a budget.
-- expect: instruction budget exhausted
-- args: 
local mt = {}
mt.__close = function() while true do end end
while true do
  pcall(coroutine.wrap(function()
    local guard <close> = setmetatable({}, mt)
    while true do end
  end))
end
