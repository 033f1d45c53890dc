-- pile.lua: sixty crates and balls dropped into a bin, one every 0.067 s from a hopper
-- moving along the top; they heap up, settle and fall asleep.  Prints, each second, how many bodies are awake
-- and the fastest one.
--   build/rigid lua/examples/pile.lua --svg build/pile.svg
duration = 10

local W, H = 4, 6                  -- inner half width and height of the bin (m)
local COUNT = 60
local bodies = {}

function setup(world)
  world:set_gravity(0, -9.81)
  world:set_sleeping(true)
  world:body{ type = "static", x = 0, y = -0.25, aabb = { W + 0.5, 0.25 }, name = "bin" }
  world:body{ type = "static", x = -W - 0.25, y = H / 2, aabb = { 0.25, H / 2 }, name = "bin" }
  world:body{ type = "static", x = W + 0.25, y = H / 2, aabb = { 0.25, H / 2 }, name = "bin" }
  math.randomseed(7)
end

-- One body from the hopper, which sweeps the width of the bin.
local function pour(world, i)
  local x, vx = (W - 0.6) * math.sin(i * 1.7), (math.random() - 0.5) * 2
  local b
  if i % 2 == 0 then
    local r = 0.2 + math.random() * 0.15
    b = world:body{ circle = r, x = x, y = H + 1, vx = vx, vy = -2, mass = 12 * r * r,
                    restitution = 0.2, friction = 0.3, name = "ball" }
  else
    local hw, hh = 0.2 + math.random() * 0.15, 0.15 + math.random() * 0.15
    b = world:body{ aabb = { hw, hh }, x = x, y = H + 1, vx = vx, vy = -2, mass = 16 * hw * hh,
                    name = "crate" }
  end
  bodies[#bodies + 1] = b
end

local t, step = 0, 0
local function fastest()
  local top = 0
  for _, b in ipairs(bodies) do
    local vx, vy = b:velocity()
    top = math.max(top, math.sqrt(vx * vx + vy * vy))
  end
  return top
end

function update(world, dt)
  t, step = t + dt, step + 1
  if step % 4 == 1 and #bodies < COUNT then pour(world, #bodies + 1) end
  if step % 60 == 0 then
    print(string.format("t = %4.1f s  awake %2d of %d  fastest %.3f m/s  touching pairs %d",
      t, world:awake_body_count(), #bodies, fastest(), world:touching_count()))
  end
end

function finish(world)
  local top = 0
  for _, b in ipairs(bodies) do
    local x, y = b:position()
    assert(x > -W and x < W and y > 0 and y < H + 2, b:name() .. " stayed in the bin")
    top = math.max(top, y)
  end
  print(string.format("settled: %d of %d bodies asleep, pile %.2f m high, fastest %.4f m/s",
    #bodies - world:awake_body_count(), #bodies, top, fastest()))
  assert(fastest() < 0.05, "the pile is at rest")
  assert(world:awake_body_count() < #bodies / 2, "most of the pile sleeps")
end
