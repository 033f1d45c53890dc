-- A script that stops the collector and keeps making garbage: at the memory cap Lua runs an
-- emergency collection anyway, so the garbage goes and the script carries on.
collectgarbage("stop")
local t = {}
for i = 1, 2e5 do t[i % 100 + 1] = { i, string.rep("x", 64) } end
assert(#t == 100)
