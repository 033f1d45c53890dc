-- A step of 150 overlapping circles of radius 1e7 is 11 175 touching pairs: physics is
-- charged by the pairs and bodies a step leaves, not per body (the creation's overlaps,
-- charged too, fit the budget; the second step does not).
-- expect: instruction budget exhausted
-- expect: steps_pairs.lua:10:
-- args: --budget 5000000
local rigid = require "rigid"
local w = rigid.world{}
for i = 1, 150 do w:body{ circle = 1e7, x = i, y = 0 } end
for i = 1, 60 do w:step(1 / 60) end
print("stepped")
