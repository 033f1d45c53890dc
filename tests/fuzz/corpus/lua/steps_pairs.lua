-- A step of 100 overlapping circles of radius 1e7 is 4 950 touching pairs: physics is
-- charged by the pairs and bodies a step leaves, not per body.
-- expect: instruction budget exhausted
-- args: 
local rigid = require "rigid"
local w = rigid.world{}
for i = 1, 100 do w:body{ circle = 1e7, x = i, y = 0 } end
for i = 1, 60 do w:step(1 / 60) end
print("stepped")
