-- == between two distinct long strings of one length compares them byte by byte inside one
-- instruction: while such a pair lives, every instruction is charged what it may compare.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local a = string.rep("x", 1 << 20)
local b = string.rep("x", 1 << 20)   -- long strings are not interned: another object
local same = 0
for i = 1, 100000 do
  if a == b then same = same + 1 end
end
print(same)
