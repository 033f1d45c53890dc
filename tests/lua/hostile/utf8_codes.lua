-- The utf8.codes iterator called by hand at a run of continuation bytes skips the run in C:
-- charged by the distance it moves, like utf8.offset.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local s = "a" .. string.rep("\x80", 1 << 20) .. "b"
local step = utf8.codes(s)
local n = 0
for i = 1, 3000 do
  n = n + (step(s, 1) or 0)
  n = n + (utf8.offset(s, 2) or 0)
end
print(n)
