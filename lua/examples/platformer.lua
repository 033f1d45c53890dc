-- platformer.lua: a character runs right through a level that uses the gameplay collision
-- of rigid.  It jumps up through two one-way ledges from below and lands on each; leaves
-- the first one's edge and still jumps a moment later (coyote time); looks down, then drops
-- through the upper ledge (body:pass_through); rides a moving platform (a kinematic
-- shuttle) across a pit it could not jump; jumps over a crate, collects the coins (sensors)
-- and reaches the flag.  What it stands on comes from body:contacts(), a ground probe
-- (world:cast_box below the feet) puts dust where it is about to land, and
-- world:raycast_all checks there is a floor under the ledge before the drop.  The "player"
-- presses jump at fixed places and once more shortly after each jump; presses in the air
-- after the coyote time do nothing.  Prints a line per second and a summary; finish()
-- checks the run.  Prints where it starts too (the replay viewer's test reads it).  This
-- is `make run`.
--   build/rigid lua/examples/platformer.lua --svg build/run.svg --html build/run.html
duration = 13

local G = 25                       -- m/s^2: arcade gravity, snappy jumps
local RUN, JUMP = 6, 11            -- m/s: run speed, take-off speed (apex JUMP^2 / 2G = 2.42 m)
local HALF_W, HALF_H = 0.35, 0.5
local COYOTE = 0.1                 -- s after leaving the ground in which a jump still counts
local SOLID, PLAYER, PICKUP = 1, 2, 4   -- collision categories
-- The shuttle: a kinematic box that carries the player over the pit (x 24 .. 36).
local SHUTTLE_LEFT, SHUTTLE_RIGHT, SHUTTLE_SPEED, DOCK_TIME = 25.2, 34.8, 3, 0.8
local SHUTTLE_PHASE = 4.2          -- s into its round when the scene starts (see shuttle_x)

local player, shuttle, upper_ledge
local coins, coins_total = 0, 0
local jumps, refused, coyote_jumps = 0, 0, 0
local landings = {}                -- what the player landed on: { name, height }
local reached_goal, lowest = false, math.huge
local t, step = 0, 0
local presses = {}                 -- x positions where the player presses jump
local next_press = 1
local mash_at                      -- a press in the air, shortly after each jump
local support, was_supported = nil, true   -- the body under the feet, from contacts()
local last_support_t, jumped = -1, false   -- for coyote time
local mode = "run"                 -- run -> wait (at the pit) -> ride -> run
local ride_time, ride_from = 0, nil
local drop = { x = 17.2, done = false, floor_below = nil, below_ledge = false }
dust = {}                          -- { x, y, t } where the probe saw the player land (hosts may draw it)

local function static_box(world, x0, x1, top, thickness, name, one_way)
  return world:body{ type = "static", x = (x0 + x1) / 2, y = top - thickness / 2,
                     aabb = { (x1 - x0) / 2, thickness / 2 }, name = name,
                     category = SOLID, one_way = one_way and { 0, 1 } or nil }
end

-- The shuttle's centre at time s: a round trip of dock, ride right, dock, ride left.
local function shuttle_x(s)
  local span = SHUTTLE_RIGHT - SHUTTLE_LEFT
  local ride = span / SHUTTLE_SPEED
  local u = (s + SHUTTLE_PHASE) % (2 * (DOCK_TIME + ride))
  if u < DOCK_TIME then return SHUTTLE_LEFT end
  u = u - DOCK_TIME
  if u < ride then return SHUTTLE_LEFT + SHUTTLE_SPEED * u end
  u = u - ride
  if u < DOCK_TIME then return SHUTTLE_RIGHT end
  return SHUTTLE_RIGHT - SHUTTLE_SPEED * (u - DOCK_TIME)
end

function setup(world)
  world:set_gravity(0, -G)
  static_box(world, -3, 24, 0, 1, "ground")
  static_box(world, 36, 60, 0, 1, "ground")
  static_box(world, 6, 12, 2.0, 0.3, "ledge", true)
  upper_ledge = static_box(world, 13, 19, 4.0, 0.3, "ledge", true)
  static_box(world, 43.4, 44.6, 1.2, 1.2, "crate")
  shuttle = world:body{ type = "kinematic", x = shuttle_x(0), y = -0.6, aabb = { 1.2, 0.2 },
                        category = SOLID, name = "shuttle" }
  world:body{ type = "static", x = 56, y = 1.5, aabb = { 0.3, 1.5 }, sensor = true,
              category = PICKUP, name = "flag" }
  for _, c in ipairs{ { 3, 1 }, { 8.9, 3.0 }, { 15.0, 5.0 }, { 20.0, 2.3 }, { 30, 0.6 },
                      { 44.1, 2.9 }, { 50, 1 }, { 30, -3 } } do
    world:body{ type = "static", x = c[1], y = c[2], circle = 0.3, sensor = true,
                category = PICKUP, name = "coin" }
    coins_total = coins_total + 1
  end
  player = world:body{ x = 0, y = HALF_H, aabb = { HALF_W, HALF_H }, friction = 0,
                       category = PLAYER, name = "player" }
  -- under the first ledge (through it from below), at its edge (coyote), over the crate
  presses = { 6.3, 12.6, 41.5 }
  local x, y = player:position()
  print(string.format("t =  0.0 s  x = %5.2f  y = %5.2f  (the start)", x, y))
end

-- The solid body the player stands on after the last step (a contact whose normal, from
-- the player toward it, points down), or nil.
local function standing_on()
  for _, c in ipairs(player:contacts()) do
    if not c.sensor and c.ny < -0.7 then return c.other end
  end
end

-- The ground probe: a thin box as wide as the feet, swept 0.5 m down from 2 cm above them,
-- against solid shapes only.  Returns the body and the gap below the feet, or nil.
local function probe(world, x, y)
  local body, _, hy = world:cast_box(HALF_W - 0.05, 0.02, x, y - HALF_H + 0.04, 0, -0.5, SOLID)
  if body then return body, y - HALF_H - hy, hy end
end

local function press_jump()
  local coyote = not support and not jumped and t - last_support_t <= COYOTE
  if support or coyote then
    local _, vy = player:velocity()
    player:apply_impulse(0, player:mass() * (JUMP - vy))
    jumps, jumped = jumps + 1, true
    if coyote then coyote_jumps = coyote_jumps + 1 end
    mash_at = t + 0.2
  else
    refused = refused + 1
  end
end

-- Look down through the ledge first: every solid surface under the feet, the ledge first.
local function drop_through(world)
  local x, y = player:position()
  local hits = world:raycast_all(x, y - HALF_H + 0.01, 0, -6, SOLID)
  if #hits >= 2 and rawequal(hits[1].body, upper_ledge) then
    drop.floor_below = hits[2].body:name()
    player:pass_through(upper_ledge)
    drop.done = true
  end
end

function update(world, dt)
  t, step = t + dt, step + 1
  local x, y = player:position()
  local vx, vy = player:velocity()
  lowest = math.min(lowest, y)
  support = standing_on()
  if support then
    if not was_supported then landings[#landings + 1] = { support:name(), y - HALF_H } end
    last_support_t, jumped = t, false
  end
  if step > 1 then was_supported = support ~= nil end   -- contacts exist from the first step

  -- the probe: about to land within this step -> dust on the surface it will land on
  local body, gap, top = probe(world, x, y)
  if body and vy < 0 and gap <= -vy * dt + 0.01 and not support then
    dust[#dust + 1] = { x = x, y = top, t = t, on = body:name() }
  end

  -- the shuttle follows its timetable: the velocity that reaches the next point in one step
  local sx = shuttle:position()
  shuttle:set_velocity((shuttle_x(t) - sx) / dt, 0)
  local svx = shuttle:velocity()

  -- Run: a force that brings vx to the target (relative to what it stands on) in ~0.15 s.
  local target = RUN
  if mode == "run" and x > 23.2 and x < 30 then mode = "wait" end
  if mode == "wait" then
    target = 0
    if math.abs(sx - SHUTTLE_LEFT) < 1e-3 then mode = "board" end   -- docked at our side
  end
  if mode == "board" or mode == "ride" then
    target = svx + math.max(-RUN, math.min(RUN, 4 * (sx - x)))     -- to its middle
    if support == shuttle then
      mode, ride_time = "ride", ride_time + dt
      ride_from = ride_from or sx
      if math.abs(sx - SHUTTLE_RIGHT) < 1e-3 then                 -- docked at the far side
        mode = "run"
        press_jump()
      end
    end
  end
  if reached_goal then target = 0 end
  if support and mode == "run" then target = target + (support:velocity()) end
  local force = player:mass() * (target - vx) / 0.15
  player:apply_force(math.max(-40, math.min(40, force)), 0)

  if presses[next_press] and x >= presses[next_press] then
    next_press = next_press + 1
    press_jump()
  elseif mash_at and t >= mash_at then
    mash_at = nil
    press_jump()                   -- in the air: refused
  end
  if not drop.done and support == upper_ledge and x >= drop.x then drop_through(world) end
  if drop.done and not drop.below_ledge and x < 19 + HALF_W and y + HALF_H < 4.0 - 0.3 then
    drop.below_ledge = true        -- all of it under the ledge: it went through
  end

  if step % 60 == 0 then
    print(string.format("t = %4.1f s  x = %5.2f  y = %5.2f  vx = %5.2f  vy = %6.2f  %-8s coins %d/%d  jumps %d  refused %d",
      t, x, y, vx, vy, support and support:name() or "in air", coins, coins_total, jumps, refused))
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
  local seen = {}
  for i, l in ipairs(landings) do seen[i] = string.format("%s %.2f", l[1], l[2]) end
  print(string.format("summary: %d/%d coins, %d jumps (%d in coyote time), %d presses in the air refused, landed on %s, dropped through the ledge onto the %s, rode the shuttle %.1f s, flag %s",
    coins, coins_total, jumps, coyote_jumps, refused, table.concat(seen, ", "),
    tostring(drop.floor_below), ride_time, reached_goal and "reached" or "missed"))
  local function landed(name, h)
    for _, l in ipairs(landings) do
      if l[1] == name and math.abs(l[2] - h) < 0.01 then return true end
    end
  end
  local function dust_on(name)
    for _, d in ipairs(dust) do if d.on == name then return true end end
  end
  assert(reached_goal, "the player reaches the flag")
  assert(coins == coins_total - 1, "every coin on the way, and not the one in the pit")
  assert(jumps == #presses + 1, "each press on the ground jumped, and the jump off the shuttle")
  assert(coyote_jumps == 1, "the press just past the ledge's edge jumped (coyote time)")
  assert(refused == jumps, "each press in the air after the coyote time was refused")
  assert(landed("ledge", 2.0) and landed("ledge", 4.0), "jumped up through both ledges and landed on them")
  assert(drop.done and drop.below_ledge and drop.floor_below == "ground", "dropped through the upper ledge")
  assert(landed("ground", 0) and landed("shuttle", -0.4), "landed on the ground after the drop, and on the shuttle")
  assert(ride_time > 2.5 and ride_from and ride_from < 26, "rode the shuttle across the pit")
  assert(dust_on("ledge") and dust_on("shuttle") and dust_on("ground"), "the probe saw each landing coming")
  assert(lowest > -0.5, "never fell into the pit")
end
