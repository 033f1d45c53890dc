-- Stepping a big world in a loop: the physics work is charged to the budget too.
-- expect: instruction budget exhausted
-- args: --budget 20000000
local rigid = require "rigid"
local w = rigid.world{ gravity = {0, -9.81} }
for i = 1, 20000 do w:body{ x = i } end
while true do w:step(1 / 60) end
