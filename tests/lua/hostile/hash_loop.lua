-- world:hash reads the world's whole state in C: charged a unit per 8 bytes of its snapshot,
-- so hashing a world of 20,000 bodies again and again runs out of budget (uncharged, each
-- hash was 0.1 ms of C for one unit).
-- expect: instruction budget exhausted
-- expect: hash_loop.lua:13:
-- args: --budget 20000000 --timeout 0
local rigid = require "rigid"
local w = rigid.world{ gravity = { 0, 0 } }
for i = 1, 20000 do w:body{ x = 3 * (i % 100), y = 3 * (i // 100), circle = 1, vx = i % 7 } end
local save = w:save()
print(("%d bodies, a snapshot of %d bytes"):format(w:body_count(), #save))
local hashes = 0
for _ = 1, 3000 do hashes = hashes + (w:hash() ~= 0 and 1 or 0) end
print(hashes .. " hashes")
