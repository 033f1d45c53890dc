-- load() of one 1 MiB chunk of blanks, again and again: each parse is charged by size.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local blanks = string.rep(" ", 1 << 20)
for i = 1, 1000 do load(blanks) end
print("parsed")
