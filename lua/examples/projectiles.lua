-- projectiles.lua: three shells fired alike, pushed by the same crosswind.  Wind is a force,
-- so the light shell drifts furthest; each path matches the closed form of the integrator.
--   build/rigid lua/examples/projectiles.lua --svg build/projectiles.svg
duration = 170 / 60    -- the shells are just above the ground at the end

local G, WIND, DT = -9.81, 1.5, 1 / 60
local V0X, V0Y = 6, 14
local shells = {}

function setup(world)
  world:set_gravity(0, G)
  world:set_wind(WIND, 0)
  world:set_fixed_step(DT)
  for i, mass in ipairs{ 0.25, 1, 4 } do
    shells[i] = { mass = mass, body = world:body{ mass = mass, vx = V0X, vy = V0Y,
                                                  name = string.format("%g kg", mass) } }
  end
  world:body{ type = "static", x = 0, y = 0, name = "cannon" }
  world:body{ type = "static", x = 20, y = -0.25, name = "ground",
              aabb = { 22, 0.25 } }
end

local steps = 0
function update(world, dt)
  steps = steps + 1
end

function finish(world)
  -- Semi-implicit Euler after n steps: x = v0 n dt + a dt^2 n (n + 1) / 2, exactly.
  local n = steps
  for _, s in ipairs(shells) do
    local ax = WIND / s.mass
    local x, y = s.body:position()
    local ex = V0X * n * DT + ax * DT * DT * n * (n + 1) / 2
    local ey = V0Y * n * DT + G * DT * DT * n * (n + 1) / 2
    print(string.format("%-7s lands at x = %6.2f m after %.2f s (closed form of the integrator: %.2f, %.3f)",
      s.body:name(), x, n * DT, ex, ey))
    assert(math.abs(x - ex) < 1e-3 * math.abs(ex) + 1e-3, "x follows the closed form")
    assert(math.abs(y - ey) < 1e-3, "y follows the closed form")
    assert(y >= 0 and y < 0.1, s.body:name() .. " is just above the ground")
    s.x = x
  end
  assert(shells[1].x > shells[2].x and shells[2].x > shells[3].x,
         "the lighter the shell, the further the wind carries it")
end
