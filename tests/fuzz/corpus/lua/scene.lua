local n = 0
function update(world, dt)
  if n == 0 then
    world:set_gravity(0, -9.81)
    world:body{ type = "static", aabb = {5, 0.5}, y = -0.5 }
    for i = 1, 8 do world:body{ circle = 0.25, x = i * 0.3 - 1.2, y = 0.2, restitution = 0.5 } end
    world:body{ aabb = {0.3, 0.3}, y = 1, drag = {0.1, 0.01}, sensor = false }
  end
  n = n + 1
  for _, e in ipairs(world:events()) do local x = e.a:position() end
  local b, hx, hy = world:raycast(0, 5, 0, -10)
end
function contact(world, e)
  if e.kind == "begin" then e.b:apply_impulse(0, 0.1) end
end
