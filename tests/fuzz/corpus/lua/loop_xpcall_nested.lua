-- Nested pcall/xpcall and an error handler that loops too.
-- expect: instruction budget exhausted
-- args: 
local function spin() while true do end end
while true do
  pcall(pcall, xpcall, spin, function() while true do end end)
  pcall(error, "again")
end
