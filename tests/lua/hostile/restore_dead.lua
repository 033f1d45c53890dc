-- world:restore looks over every body value the script holds, destroyed bodies' too, in C:
-- charged by their count, so restores of an empty world's snapshot while 20,000 values of
-- destroyed bodies are held run out of budget (uncharged, each was 1 ms of C for a few units).
-- expect: instruction budget exhausted
-- expect: restore_dead.lua:16:
-- args: --budget 20000000 --timeout 0
local rigid = require "rigid"
local w = rigid.world{}
local held = {}
for i = 1, 20000 do held[i] = w:body{ x = 3 * i, circle = 1 } end
for i = 1, 20000 do held[i]:destroy() end
local empty = w:save()
collectgarbage()
print("holding " .. #held .. " destroyed bodies")
local restored = 0
for _ = 1, 300 do w:restore(empty) restored = restored + 1 end
print(restored .. " restores")
