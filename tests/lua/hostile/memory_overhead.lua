-- 200 000 empty tables ask for 15.4 MB with their array, but malloc spends 64 bytes on each
-- 56-byte table (17 MB): the cap counts blocks as malloc sizes them.
-- expect: not enough memory
-- expect: last seen at
-- args: --memory 16
-- traceback: no
local t = {}
for i = 1, 200000 do t[i] = {} end
print(collectgarbage("count"))
