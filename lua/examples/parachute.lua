-- parachute.lua: a skydiver drops from 300 m, falls with little drag, opens the canopy at
-- 3 s (it fills over 1.5 s) and settles at the terminal speed sqrt(m g / k) of quadratic
-- drag, drifting with the wind.  Prints one line per second.
--   build/rigid lua/examples/parachute.lua --svg build/parachute.svg
duration = 12

local M, G = 80, 9.81
local K_FREE, K_CANOPY = 0.25, 30          -- kg/m: 1/2 rho Cd A, body and canopy
local diver, opened
local t, next_print = 0, 1

function setup(world)
  world:set_gravity(0, -G)
  world:set_wind(40, 0)
  diver = world:body{ mass = M, y = 300, vx = 20, drag = { 0, K_FREE }, name = "skydiver" }
  world:body{ type = "static", x = 0, y = 300, name = "plane" }
end

function update(world, dt)
  t = t + dt
  if t >= 3 then
    opened = opened or t
    local fill = math.min(1, (t - opened) / 1.5)
    diver:set_drag(0, K_FREE + (K_CANOPY - K_FREE) * fill)
  end
  if t >= next_print then
    local x, y = diver:position()
    local vx, vy = diver:velocity()
    print(string.format("t = %4.1f s  x = %6.1f m  y = %6.1f m  fall speed = %5.2f m/s%s",
      t, x, y, -vy, opened and "  canopy open" or ""))
    next_print = next_print + 1
  end
end

function finish(world)
  local _, vy = diver:velocity()
  local terminal = math.sqrt(M * G / K_CANOPY)
  print(string.format("terminal speed sqrt(m g / k) = %.3f m/s; reached %.3f m/s", terminal, -vy))
  assert(math.abs(-vy - terminal) < 0.01 * terminal, "terminal speed within 1%")
  local _, y = diver:position()
  assert(y > 0, "still in the air")
end
