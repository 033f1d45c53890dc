-- platformer.lua: a character runs right, jumps (only when grounded) over a gap, up two
-- platforms and over a crate, collects coins (sensors) and reaches the flag.  The "player"
-- presses jump at fixed places and also mashes it in the air; presses in the air do
-- nothing.  Prints a line per second and a summary.  This is `make run`.
--   build/rigid lua/examples/platformer.lua --svg build/run.svg
duration = 9

local G = 25                       -- m/s^2: arcade gravity, snappy jumps
local RUN, JUMP = 6, 11            -- m/s: run speed, take-off speed (apex JUMP^2 / 2G = 2.4 m)
local HALF_W, HALF_H = 0.35, 0.5

local player
local coins, coins_total = 0, 0
local jumps, refused = 0, 0
local landings = {}                -- heights the player landed at
local reached_goal, lowest = false, math.huge
local was_grounded = false
local t, step = 0, 0
local presses = {}                 -- x positions where the player presses jump
local next_press = 1
local mash_at                      -- a press in the air, shortly after each jump

local function static_box(world, x0, x1, top, thickness, name)
  return world:body{ type = "static", x = (x0 + x1) / 2, y = top - thickness / 2,
                     aabb = { (x1 - x0) / 2, thickness / 2 }, name = name }
end

function setup(world)
  world:set_gravity(0, -G)
  static_box(world, -3, 12, 0, 1, "ground")
  static_box(world, 15, 44, 0, 1, "ground")
  static_box(world, 19, 23, 2.2, 0.4, "platform")
  static_box(world, 25, 29, 4.4, 0.4, "platform")
  static_box(world, 33.4, 34.6, 1.2, 1.2, "crate")
  world:body{ type = "static", x = 42, y = 1.5, aabb = { 0.3, 1.5 }, sensor = true, name = "flag" }
  for _, c in ipairs{ { 5, 1 }, { 13.4, 2.6 }, { 19.9, 3.6 }, { 26.5, 5.3 }, { 31.5, 6.6 },
                      { 37, 1 }, { 13.4, -3 } } do
    world:body{ type = "static", x = c[1], y = c[2], circle = 0.3, sensor = true, name = "coin" }
    coins_total = coins_total + 1
  end
  player = world:body{ x = 0, y = HALF_H, aabb = { HALF_W, HALF_H }, friction = 0, name = "player" }
  presses = { 10.5, 16.6, 22.0, 28.3 }
end

local function press_jump()
  if player:grounded() then
    local _, vy = player:velocity()
    player:apply_impulse(0, player:mass() * (JUMP - vy))
    jumps = jumps + 1
    mash_at = t + 0.2
  else
    refused = refused + 1
  end
end

function update(world, dt)
  t, step = t + dt, step + 1
  local x, y = player:position()
  local vx, vy = player:velocity()
  local grounded = player:grounded()
  lowest = math.min(lowest, y)
  if grounded and not was_grounded and step > 1 then
    landings[#landings + 1] = y - HALF_H
  end
  was_grounded = grounded

  -- Run: a force that brings vx to the target speed in about 0.15 s.
  local target = reached_goal and 0 or RUN
  local force = player:mass() * (target - vx) / 0.15
  player:apply_force(math.max(-40, math.min(40, force)), 0)

  if presses[next_press] and x >= presses[next_press] then
    next_press = next_press + 1
    press_jump()
  elseif mash_at and t >= mash_at then
    mash_at = nil
    press_jump()                   -- in the air: refused
  end

  if step % 60 == 0 then
    print(string.format("t = %4.1f s  x = %5.2f  y = %5.2f  vx = %5.2f  vy = %6.2f  %-8s coins %d/%d  jumps %d  refused %d",
      t, x, y, vx, vy, grounded and "grounded" or "in air", coins, coins_total, jumps, refused))
  end
end

function contact(world, e)
  if e.kind ~= "begin" or not e.sensor then return end
  local other = (e.a == player) and e.b or (e.b == player) and e.a or nil
  if not other then return end
  if other:name() == "coin" and other:is_valid() then
    other:destroy()
    coins = coins + 1
  elseif other:name() == "flag" then
    reached_goal = true
  end
end

function finish(world)
  local heights = {}
  for i, h in ipairs(landings) do heights[i] = string.format("%.2f", h) end
  print(string.format("summary: %d/%d coins, %d jumps, %d presses in the air refused, landed at heights %s, flag %s",
    coins, coins_total, jumps, refused, table.concat(heights, ", "), reached_goal and "reached" or "missed"))
  local function landed_at(h)
    for _, l in ipairs(landings) do if math.abs(l - h) < 0.05 then return true end end
  end
  assert(reached_goal, "the player reaches the flag")
  assert(coins == coins_total - 1, "every coin on the way, and not the one under the gap")
  assert(jumps == #presses, "each press on the ground jumped")
  assert(refused == jumps, "each press in the air was refused")
  assert(landed_at(2.2) and landed_at(4.4), "landed on both platforms")
  assert(lowest > 0, "never fell into the gap")
end
