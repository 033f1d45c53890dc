-- 1500 overlapping circles of radius 1e7 would make 1.1 million pairs in the first step,
-- which the step charges only once it has run: the overlaps are charged as shapes are made.
-- expect: instruction budget exhausted
-- expect: crowd_creation.lua:8:
-- args: --budget 200000 --memory 16
local rigid = require "rigid"
local w = rigid.world{}
for i = 1, 1500 do w:body{ circle = 1e7, x = i, y = 0 } end
w:step(1 / 60)
print("stepped")
