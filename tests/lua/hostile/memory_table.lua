-- Growing a table without end.
-- expect: not enough memory
-- expect: last seen at
-- args: --memory 16
-- traceback: no
local t = {}
for i = 1, math.maxinteger do t[i] = { i } end
