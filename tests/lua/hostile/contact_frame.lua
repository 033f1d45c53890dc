-- Hundreds of contact events in one frame, each handler spending a fifth of the budget: the
-- update and the contact calls of a frame share one budget.
-- expect: contact failed
-- expect: instruction budget exhausted
-- args: --budget 1000000 --steps 3
function setup(world)
  world:body{ type = "static", aabb = {100, 0.5}, y = -0.5 }
  for i = 1, 400 do world:body{ circle = 0.5, x = (i - 200) * 0.45, y = 0.4 } end
end
function contact(world, e)
  local x = 0
  for i = 1, 100000 do x = x + i end
end
