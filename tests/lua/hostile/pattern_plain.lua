-- A plain find whose every candidate compares a long needle: n * m work in one call.
-- expect: instruction budget exhausted
-- args: --budget 2000000
local hay = string.rep("a", 2000000)
local needle = string.rep("a", 1000000) .. "b"
while true do hay:find(needle, 1, true) end
