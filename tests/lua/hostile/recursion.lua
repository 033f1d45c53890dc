-- Unbounded recursion.  Lua's 1 000 000-slot stack limit takes about 72 MB of real memory
-- (CallInfo blocks and the stack), past the default 64 MiB cap now that the cap counts what
-- malloc spends: given room, the depth limit is what stops it.
-- expect: stack overflow
-- args: --memory 128
local function f(n) return 1 + f(n + 1) end
f(1)
