-- Physics memory counts against the cap too: bodies without end.
-- expect: world:body: out of memory (body storage)
-- args: --memory 16
local rigid = require "rigid"
local w = rigid.world()
local i = 0
while true do i = i + 1; w:body{ x = i } end
