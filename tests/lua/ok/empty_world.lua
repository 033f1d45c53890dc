-- A scene with no bodies at all: the host advances the world every step, and a script
-- steps and advances one too.  Must run cleanly (under the sanitizers too).
local rigid = require "rigid"
local w = rigid.world()
w:step(1 / 60)
assert(w:advance(1 / 30) == 2, "two fixed steps")
assert(#w:bodies() == 0 and w:body_count() == 0)
function update(world, dt)
  assert(world:body_count() == 0)
end
