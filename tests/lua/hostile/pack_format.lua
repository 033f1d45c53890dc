-- string.pack, unpack and packsize read their format byte by byte in C: packsize of 300 000
-- padding bytes "x", 2 000 times (uncharged: 3.2 s for about ten thousand units; one
-- long string alone, so no comparison is charged either).  Charged per byte of the format.
-- expect: instruction budget exhausted
-- args: --budget 20000000
local fmt = string.rep("x", 300000)
local n = 0
for k = 1, 2000 do n = n + string.packsize(fmt) end
print(n)
