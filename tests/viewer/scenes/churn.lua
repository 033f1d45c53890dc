-- churn.lua: bodies made and destroyed every few steps, shapes changed and cleared, a body
-- teleported, names with markup and bytes that are not UTF-8, a spring, and a print that
-- stops mid-line with an error in __tostring.  The replay must read all of it.
duration = 2
local made, step = {}, 0
local spinner, hopper

function setup(world)
  world:set_gravity(0, -9.81)
  world:body{ type = "static", y = -0.5, aabb = { 10, 0.5 }, name = "</script><script>document.body.dataset.error='injected'</script>" }
  spinner = world:body{ x = -3, y = 2, circle = 0.3, name = "bad \255\254 bytes \226\130" }
  hopper = world:body{ x = 3, y = 3, name = "no shape yet" }
  world:spring{ a = hopper, anchor = { 3, 5 }, rest_length = 1, stiffness = 40, damping = 2 }
  print("setup: 3 bodies and a spring")
end

function update(world, dt)
  step = step + 1
  if step % 5 == 0 then
    made[#made + 1] = world:body{ x = (step % 7) - 3, y = 4, circle = 0.2, name = "drop " .. step }
  end
  if step % 11 == 0 and #made > 0 then table.remove(made, 1):destroy() end
  if step == 30 then hopper:set_circle(0.25) end
  if step == 60 then spinner:set_aabb(0.4, 0.2) end
  if step == 80 then hopper:clear_shape() end
  if step == 90 then spinner:set_position(4, 1) end
  if step == 100 then
    print("a line with a tab\tand a NUL \0 inside")
    pcall(print, "before the error", setmetatable({}, { __tostring = function() error("no") end }))
  end
end
