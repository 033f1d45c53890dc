-- The binding's integer arguments take strings of digits as Lua's own do, reading all of
-- the string in C: charged by its length, so a loop passing 1 MiB of digits runs out of
-- budget (uncharged, each call was 0.9 ms of C for a unit).
-- expect: instruction budget exhausted
-- expect: integer_string.lua:12:
-- args: --budget 2000000 --timeout 0
local rigid = require "rigid"
local w = rigid.world{}
local b = w:body{ circle = 1 }
local digits = string.rep("0", 1 << 20) .. "7"
collectgarbage()
for _ = 1, 200 do b:set_user_data(digits) w:drop_slot(digits) end
print("user data " .. b:user_data())
