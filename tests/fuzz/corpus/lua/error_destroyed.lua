-- Using a destroyed body from a scene's update.
-- expect: update failed
-- expect: attempt to use a destroyed body
local ball
function setup(world) ball = world:body{ name = "ball" } end
function update(world, dt)
  ball:destroy()
  ball:apply_force(1, 0)
end
