-- An infinite loop that catches the budget error and carries on: it cannot.
-- expect: instruction budget exhausted
-- args: 
local caught = 0
while true do
  local ok = pcall(function() while true do end end)
  if not ok then caught = caught + 1 end
end
