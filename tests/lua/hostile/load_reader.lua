-- load() with a reader that hands the parser 1 MiB of blanks again and again: the parser
-- runs in C, so its input is charged by size.
-- expect: instruction budget exhausted
-- args: --budget 1000000
local blanks = string.rep(" ", 1 << 20)
local pieces = 0
local f, err = load(function()
  pieces = pieces + 1
  if pieces <= 1000 then return blanks end
end)
print(pieces, f, err)
