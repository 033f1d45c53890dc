-- Unbounded recursion through C functions (gsub calling back into Lua).
-- expect: stack overflow
local function f(s) return (string.gsub("x", "x", f)) end
f("x")
