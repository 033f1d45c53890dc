-- A NaN force from a script: a clear error from the binding, nothing reaches the world.
-- expect: bad argument #1 to 'apply_force' (finite number expected, got nan)
local rigid = require "rigid"
local w = rigid.world()
local b = w:body{}
b:apply_force(0 / 0, 0)
