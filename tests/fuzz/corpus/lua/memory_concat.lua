-- Strings piling up in a table, with pcall trying to keep going.  Lua raises memory
-- errors without a message handler, so there is no traceback: the host says where the
-- script was last seen.
-- expect: not enough memory
-- expect: memory cap of 16 MiB
-- expect: last seen at
-- args: --memory 16
-- traceback: no
local t, chunk = {}, string.rep("y", 1000)
while true do
  local ok, err = pcall(function()
    for i = 1, 1000 do t[#t + 1] = chunk .. #t end
  end)
  if not ok then error(err, 0) end
end
