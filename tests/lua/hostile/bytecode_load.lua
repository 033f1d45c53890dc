-- Loading a binary chunk: load takes text only, whatever mode is asked for.
-- expect: attempt to load a binary chunk
local chunk = "\27Lua\84\0\25\147\13\10\26\10\4\8\8\120\86\0\0\0\0\0\0\0\0\0\0\0\40\119\64\1"
local f, err = load(chunk, "=bytes", "b")
if not f then error(err) end
f()
