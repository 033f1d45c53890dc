-- gsub and gmatch with a quadratic pattern on a long subject.
-- expect: instruction budget exhausted
-- args: 
local s = string.rep("a", 200000)
for m in s:gmatch("a*b") do print(m) end
print(s:gsub("(a-)%1b", "x"))
