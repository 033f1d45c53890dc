-- A contact handler that never returns.
-- expect: contact failed
-- expect: instruction budget exhausted
-- args: 
function setup(world)
  world:set_gravity(0, -10)
  world:body{ type = "static", aabb = {5, 0.5}, y = -0.5 }
  world:body{ circle = 0.5, y = 2 }
end
function contact(world, e)
  e.a:destroy()
  while true do end
end
