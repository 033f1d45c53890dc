-- Infinite loops inside coroutines, resumed from a loop that swallows their errors.
-- expect: instruction budget exhausted
-- args: 
while true do
  local co = coroutine.create(function() while true do end end)
  coroutine.resume(co)
  pcall(coroutine.wrap(function() while true do coroutine.yield() end end))
  local inner = coroutine.wrap(function()
    local co2 = coroutine.create(function() while true do end end)
    return coroutine.resume(co2)
  end)
  pcall(inner)
end
