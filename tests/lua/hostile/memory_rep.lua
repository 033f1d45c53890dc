-- A string bigger than the memory cap, asked for in one call.
-- expect: would not fit in the memory cap (16 MiB)
-- args: --memory 16
local s = string.rep("x", 1 << 30)
print(#s)
