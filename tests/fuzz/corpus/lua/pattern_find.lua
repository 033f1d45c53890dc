-- A pattern that backtracks cubically over 100 000 characters: hours for the stock matcher.
-- expect: instruction budget exhausted
-- args: 
local s = string.rep("a", 100000)
print(s:find(".-.-.-b"))
