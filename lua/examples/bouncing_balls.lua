-- bouncing_balls.lua: five frictionless balls thrown gently along five shelves, restitution
-- 0 to 0.95.
-- Each bounce turns at the shelf and leaves at e times the speed it hit it with (impacts
-- slower than the world's 1 m/s restitution threshold do not bounce), so each arc is e^2 as
-- high as the one before.  Prints every bounce of the 0.5 ball.
--   build/rigid lua/examples/bouncing_balls.lua --svg build/bouncing_balls.svg
duration = 6

local R, DROP, VX, GAP = 0.25, 3, 1.3, 4
local balls = {}

function setup(world)
  world:set_gravity(0, -9.81)
  for i, e in ipairs{ 0, 0.25, 0.5, 0.75, 0.95 } do
    local top = -(i - 1) * GAP                  -- each ball has a shelf of its own
    world:body{ type = "static", aabb = { 5, 0.15 }, x = 4.5, y = top - 0.15, name = "shelf" }
    local b = world:body{ circle = R, x = 0, y = top + DROP, vx = VX, restitution = e, friction = 0,
                          name = string.format("e = %.2f", e) }
    balls[b] = { e = e, bounces = {}, apexes = {}, top = top }
    balls[#balls + 1] = b
  end
end

-- Each apex after a bounce, from the velocity turning downwards.
local last_vy = {}
function update(world, dt)
  for _, b in ipairs(balls) do
    local info = balls[b]
    local _, vy = b:velocity()
    local _, y = b:position()
    if last_vy[b] and last_vy[b] > 0 and vy <= 0 then info.apexes[#info.apexes + 1] = y end
    last_vy[b] = vy
  end
end

-- contact() runs after the step in which a ball met its shelf, with the speed it came in
-- at when that step began; the ball's velocity is already the one it leaves with.
function contact(world, e)
  if e.kind ~= "begin" then return end
  local ball = balls[e.a] and e.a or e.b
  local info = balls[ball]
  if not info then return end
  local _, out = ball:velocity()
  info.bounces[#info.bounces + 1] = { speed_in = e.speed, speed_out = out }
  if info.e == 0.5 then
    print(string.format("e = 0.50 meets its shelf at %5.2f m/s and leaves at %5.2f m/s", e.speed, out))
  end
end

function finish(world)
  local G, DT = 9.81, 1 / 60
  for _, b in ipairs(balls) do
    local info = balls[b]
    local first = info.bounces[1]
    print(string.format("%s: %d contacts; first bounce %.2f m/s in, %.2f m/s out (ratio %.3f); first apex %.3f m",
      b:name(), #info.bounces, first.speed_in, first.speed_out, first.speed_out / first.speed_in,
      info.apexes[1] or 0))
    for _, bounce in ipairs(info.bounces) do
      if bounce.speed_in > 1 and info.e > 0 then      -- above the restitution threshold
        -- The ball meets the shelf a fraction t into the step, having gained up to (1/2 + t) g dt
        -- on the speed the step began with (speed_in), and leaves at e times that; gravity
        -- then slows it for the rest of the step.  So speed_out - e * speed_in lies in
        -- [-(1 - e) g dt / 2, (3 e + 1) g dt / 2].
        local d = bounce.speed_out - info.e * bounce.speed_in
        assert(d >= -(1 - info.e) * G * DT / 2 - 1e-4 and d <= (3 * info.e + 1) * G * DT / 2 + 1e-4,
               "leaves at e times the speed it hit the shelf with")
      end
    end
    if info.e > 0 then
      -- Dropped from rest DROP - R above its resting height, the ball rises back to e^2 times
      -- that.  Semi-implicit Euler keeps 1/2 v^2 + g y - 1/2 g dt v exactly in flight and the
      -- bounce scales it by e^2 up to (1 - e^2) g dt^2 / 8, the highest sample of an arc lies
      -- within g dt^2 / 8 above that, and the one recorded (where vy turns) within g dt^2
      -- below the highest.  1e-4 m covers float rounding over the fall.
      local want = info.top + R + info.e ^ 2 * (DROP - R)
      local below, above = (1 + 1 / 8) * G * DT ^ 2 + 1e-4, G * DT ^ 2 / 8 + 1e-4
      assert(info.apexes[1] > want - below and info.apexes[1] < want + above,
             string.format("apex %.4f m, theory e^2 times the drop: %.4f m", info.apexes[1], want))
    else
      assert(#info.apexes == 0, "e = 0 does not bounce")
    end
  end
  for _, b in ipairs(balls) do
    if balls[b].e <= 0.5 then
      local _, y = b:position()
      assert(math.abs(y - balls[b].top - R) < 0.01 and b:grounded(), b:name() .. " rests on its shelf")
    end
  end
end
