-- With --html the host's print also logs each line for the replay; it is charged by the
-- bytes it writes as the sandbox's own print is (print_long.lua), not uncharged.
-- expect: instruction budget exhausted
-- args: --budget 200000 --html $OUT/print_html.html
local s = string.rep("x", 1 << 16)
for i = 1, 100 do print(s) end
