-- rain.lua: N circles (radius 0.5 m, default 4000) start on the jittered grid of the
-- benchmark's "rain" scene (0.1 m apart), but thrown sideways and down at up to 2 m/s, so
-- they collide in flight and tumble into a heap instead of landing in columns; the heap
-- settles and falls asleep.  Prints,
-- each second, how many are awake, the fastest and the top of the heap.  The big scene of
-- the replay viewer (10 s = 600 steps):
--   build/rigid lua/examples/rain.lua --html build/rain.html [-- N]
-- needs: collision
duration = 10

local N = math.tointeger(tonumber((...) or 4000))
assert(N and N >= 1 and N <= 100000, "rain.lua: N must be a whole number from 1 to 100000")
local R = 0.5
local inner = math.ceil(math.sqrt(N)) + 0.5      -- inner width of the bin (m)
local half = inner / 2
local cols = math.floor((inner - 1.08) / 1.1) + 1
local rows = (N + cols - 1) // cols
local wall_top = 1 + 1.1 * rows + 2
local balls = {}
local t = 0

function setup(world)
  world:set_gravity(0, -10)
  world:set_sleeping(true)
  world:body{ type = "static", x = 0, y = -0.5, aabb = { half + 1, 0.5 }, name = "floor" }
  world:body{ type = "static", x = -half - 0.5, y = wall_top / 2, aabb = { 0.5, wall_top / 2 }, name = "wall" }
  world:body{ type = "static", x = half + 0.5, y = wall_top / 2, aabb = { 0.5, wall_top / 2 }, name = "wall" }
  math.randomseed(4000)
  local x0 = -1.1 * (cols - 1) / 2
  for i = 0, N - 1 do
    local x = x0 + 1.1 * (i % cols) + 0.08 * (math.random() - 0.5)
    local y = 1 + 1.1 * (i // cols) + 0.08 * (math.random() - 0.5)
    local vx, vy = 4 * (math.random() - 0.5), -2 * math.random()
    balls[#balls + 1] = world:body{ circle = R, x = x, y = y, vx = vx, vy = vy,
                                    mass = math.pi * R * R, name = i == 0 and "first" or nil }
  end
end

local function survey(world)
  local fastest, top, awake = 0, 0, 0
  for _, b in ipairs(balls) do
    local _, y = b:position()
    local vx, vy = b:velocity()
    fastest = math.max(fastest, math.sqrt(vx * vx + vy * vy))
    top = math.max(top, y + R)
    if b:is_awake() then awake = awake + 1 end
  end
  return awake, fastest, top
end

function update(world, dt)
  t = t + dt
  if math.abs(t - math.floor(t + 0.5)) < dt / 2 then
    local awake, fastest, top = survey(world)
    print(string.format("t = %4.1f s  awake %4d of %d  fastest %5.2f m/s  top of the heap %5.2f m",
                        t, awake, N, fastest, top))
  end
end

function finish(world)
  local escaped = 0
  for _, b in ipairs(balls) do
    local x, y = b:position()
    if math.abs(x) > half - R + 0.05 or y < R - 0.05 then escaped = escaped + 1 end
  end
  local awake, fastest, top = survey(world)
  print(string.format("summary: %d balls, %d outside the bin, %d awake, fastest %.3f m/s, heap %.2f m high",
                      N, escaped, awake, fastest, top))
  assert(escaped == 0, "every ball stays in the bin (within 5 cm of its walls and floor)")
end
