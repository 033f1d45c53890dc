-- find looks through its whole pattern for special characters before it searches: a 10 000
-- byte pattern costs its length per call, even against an empty subject.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local needle = string.rep("a", 10000) .. "b"
local n = 0
for i = 1, 20000 do
  if ("x"):find(needle) then n = n + 1 end
end
print(n)
