-- test_gameplay.lua: the Lua API of rigid's gameplay collision: one-way shapes, passing
-- through, a body's contacts with their impulses, the queries (raycast_all, query_point,
-- cast_circle, cast_box) and the character mover (body:move).  Runs where
-- tests/lua/test_rigid.lua runs: in the sandboxed host, in stock lua5.4 and in LuaJIT
-- through lua/rigid_jit.lua, one script for all.  (Its few helpers repeat test_rigid.lua's:
-- the sandbox loads no second file.)  Prints "N passed, N failed" and fails when anything
-- failed.
local rigid = require(jit and "rigid_jit" or "rigid")
local unpack = table.unpack or unpack

local passed, failed = 0, 0

local function test(name, f)
  local ok, err = pcall(f)
  if ok then passed = passed + 1 else
    failed = failed + 1
    print("FAIL " .. name .. ": " .. tostring(err))
  end
end

local function check(cond, what) if not cond then error(what or "check failed", 2) end end

local function eq(a, b, what)
  if a ~= b then error(("%s: expected %s, got %s"):format(what or "value", tostring(b), tostring(a)), 2) end
end

local function near(a, b, tol, what)
  if type(a) ~= "number" or math.abs(a - b) > tol then
    error(("%s: expected %.9g (+-%g), got %s"):format(what or "value", b, tol, tostring(a)), 2)
  end
end

-- f(...) must raise an error whose message contains `text` (plain).
local function raises(text, f, ...)
  local ok, err = pcall(f, ...)
  if ok then error("expected an error containing '" .. text .. "', got none", 2) end
  if not tostring(err):find(text, 1, true) then
    error("expected an error containing '" .. text .. "', got: " .. tostring(err), 2)
  end
end

local FLOAT = rigid.real_size == 4
local EPS = FLOAT and 2 ^ -23 or 2 ^ -52   -- rg_real's machine epsilon
local SLOP = 0.005                         -- the default contact slop (rigid.h)
local DT = 1 / 60
local G = 10

local function steps(w, n) for _ = 1, n do w:step(DT) end end

local function world_with_floor()
  local w = rigid.world{ gravity = {0, -G} }
  local floor = w:body{ type = "static", aabb = {20, 0.5}, y = -0.5, name = "floor" }
  return w, floor
end

-- ---------------------------------------------------------------- one-way shapes

test("one_way: option, setter and getter; (0, 0) is two-way", function()
  local w = rigid.world()
  local p = w:body{ type = "static", aabb = {2, 0.1}, one_way = {0, 1} }
  local nx, ny = p:one_way()
  eq(nx, 0); eq(ny, 1)
  p:set_one_way(0.6, 0.8)
  nx, ny = p:one_way()
  near(nx, 0.6, 2 * EPS, "stored normalised"); near(ny, 0.8, 2 * EPS)
  p:set_one_way(0, 0)
  nx, ny = p:one_way()
  eq(nx, 0); eq(ny, 0)
  eq(select("#", w:body{}:one_way()), 2, "a body is two-way by default")
  nx, ny = w:body{}:one_way()
  eq(nx, 0); eq(ny, 0)
end)

test("one_way: bad normals raise and change nothing", function()
  local w = rigid.world()
  local p = w:body{ type = "static", aabb = {2, 0.1}, one_way = {0, 1} }
  raises("set_one_way: normal (0.5, 0) has length 0.5, not 1", p.set_one_way, p, 0.5, 0)
  raises("set_one_way: normal (0, 1.01) has length 1.01, not 1", p.set_one_way, p, 0, 1.01)
  raises("finite number expected, got nan", p.set_one_way, p, 0 / 0, 1)
  raises("finite number expected, got inf", p.set_one_way, p, 0, math.huge)
  raises("number expected, got no value", p.set_one_way, p, 1)
  raises("number expected, got string", p.set_one_way, p, "0", 1)
  raises("rigid.body expected, got rigid.world", p.set_one_way, w, 0, 1)
  raises("rigid.body expected, got nil", p.one_way, nil)
  local nx, ny = p:one_way()
  eq(nx, 0, "unchanged"); eq(ny, 1, "unchanged")
  local n = w:body_count()
  raises("world:body: option 'one_way': normal (0.5, 0.5) has length 0.7071", w.body, w,
         { aabb = {1, 1}, one_way = {0.5, 0.5} })
  raises("option 'one_way' must be a table {a, b} of two numbers (got number)", w.body, w,
         { one_way = 1 })
  raises("option 'one_way' must hold finite numbers", w.body, w, { one_way = {0, 0 / 0} })
  raises("option 'one_way' must be a table {a, b} of two numbers", w.body, w, { one_way = {0} })
  eq(w:body_count(), n, "failed creations left nothing")
end)

-- The platform's top face is at y = 0.1; a box of half size 0.25 rests at y = 0.35, at
-- most the slop into it.
local function resting_on(y, top, half, what)
  check(y <= top + half + 1e-6 and y >= top + half - SLOP,
        ("%s: y = %.6f, resting on the top at %g needs [%g, %g]"):format(what, y, top, top + half - SLOP,
                                                                        top + half))
end

test("one_way: a falling body lands on the platform and rests within the slop", function()
  local w = rigid.world{ gravity = {0, -G} }
  w:body{ type = "static", aabb = {2, 0.1}, one_way = {0, 1}, name = "platform" }
  local crate = w:body{ aabb = {0.25, 0.25}, x = -1, y = 3 }
  local ball = w:body{ circle = 0.25, x = 1, y = 2 }
  steps(w, 180)
  resting_on(select(2, crate:position()), 0.1, 0.25, "crate")
  resting_on(select(2, ball:position()), 0.1, 0.25, "ball")
  check(crate:grounded() and ball:grounded(), "grounded on the platform")
end)

test("one_way: a body jumping up through it flies as if it were not there, then lands on top", function()
  local w, free = rigid.world{ gravity = {0, -G} }, rigid.world{ gravity = {0, -G} }
  w:body{ type = "static", aabb = {2, 0.1}, y = 1, one_way = {0, 1} }   -- top at 1.1
  local b = w:body{ aabb = {0.25, 0.25}, y = 0.3, vy = 6 }
  local f = free:body{ aabb = {0.25, 0.25}, y = 0.3, vy = 6 }
  -- v0 = 6 m/s: the bottom rises to 0.05 + 36 / 20 = 1.85 m, well above the top
  local went_above, k = false, 0
  repeat
    w:step(DT); free:step(DT); k = k + 1
    local y, fy = select(2, b:position()), select(2, f:position())
    local vy, fvy = select(2, b:velocity()), select(2, f:velocity())
    check(y == fy and vy == fvy, ("step %d: not slowed (y %.9g vs %.9g)"):format(k, y, fy))
    check(not b:grounded(), "not grounded while passing")
    went_above = went_above or y - 0.25 > 1.1
  until fvy <= 0 or k > 60
  check(went_above, "the bottom cleared the top")
  steps(w, 120)
  resting_on(select(2, b:position()), 1.1, 0.25, "landed on top")
  check(b:grounded(), "grounded on top")
end)

test("one_way: a fast body from above still lands on a thin platform", function()
  local w = rigid.world{ gravity = {0, -G} }
  w:body{ type = "static", aabb = {2, 0.01}, one_way = {0, 1} }   -- 2 cm thick
  local b = w:body{ circle = 0.1, y = 3, vy = -120 }              -- 2 m per step
  steps(w, 120)
  resting_on(select(2, b:position()), 0.01, 0.1, "landed")
end)

test("one_way: walking into its side while overlapping it is not pushed", function()
  local w = world_with_floor()
  w:body{ type = "static", aabb = {1, 0.1}, x = 3, y = 0.3, one_way = {0, 1} }   -- y 0.2 .. 0.4
  local walker = w:body{ aabb = {0.25, 0.25}, y = 0.25, friction = 0 }          -- y 0 .. 0.5
  steps(w, 30)
  local y0 = select(2, walker:position())
  walker:set_velocity(3, 0)
  for k = 1, 120 do
    w:step(DT)
    near(select(2, walker:position()), y0, SLOP, "step " .. k .. ": not pushed up")
    near(walker:velocity(), 3, 1e-4, "step " .. k .. ": not slowed")
  end
  check(walker:position() > 5.5, "through and past the platform's far end (x = 4)")
end)

test("one_way: a wall facing +x stops what comes from +x and lets the rest pass", function()
  local w = rigid.world()
  w:body{ type = "static", aabb = {0.1, 2}, one_way = {1, 0} }
  local from_right = w:body{ circle = 0.2, x = 2, y = 1, vx = -4 }
  local from_left = w:body{ circle = 0.2, x = -2, y = -1, vx = 4 }
  steps(w, 60)
  check(from_right:position() >= 0.1 + 0.2 - SLOP, "stopped at the face")
  check(from_left:position() > 1.5, "passed through")
end)

-- ---------------------------------------------------------------- pass_through

test("pass_through: a resting body drops through a platform and lands on the floor", function()
  local w = world_with_floor()
  local p = w:body{ type = "static", aabb = {2, 0.1}, y = 2, one_way = {0, 1}, name = "platform" }
  local b = w:body{ aabb = {0.25, 0.25}, y = 2.5 }
  steps(w, 60)
  resting_on(select(2, b:position()), 2.1, 0.25, "on the platform")
  b:pass_through(p)
  steps(w, 120)
  resting_on(select(2, b:position()), 0, 0.25, "dropped to the floor")
end)

test("pass_through: on a two-way shelf the pair collides again once apart", function()
  local w = world_with_floor()
  local shelf = w:body{ type = "static", aabb = {1, 0.1}, y = 2 }    -- underside at 1.9
  local c = w:body{ aabb = {0.25, 0.25}, y = 2.5 }
  steps(w, 60)
  resting_on(select(2, c:position()), 2.1, 0.25, "on the shelf")
  shelf:pass_through(c)                                             -- either order
  steps(w, 120)
  resting_on(select(2, c:position()), 0, 0.25, "through to the floor")
  -- thrown up at 8 m/s (apex 0.25 + 64 / 20 = 3.45 m without the shelf): stopped below it
  c:set_velocity(0, 8)
  local top = 0
  for _ = 1, 90 do w:step(DT); top = math.max(top, select(2, c:position())) end
  check(top <= 1.9 - 0.25 + SLOP, "hit the underside: top " .. top)
  check(top > 1.9 - 0.25 - 0.2, "and got near it: top " .. top)
end)

test("pass_through: bad arguments raise", function()
  local w, floor = world_with_floor()
  local other = rigid.world()
  local b = w:body{ circle = 0.2, y = 0.2 }
  local bare = w:body{ y = 5 }
  local foreign = other:body{ circle = 1 }
  raises("pass_through: other is body (a pair is two bodies)", b.pass_through, b, b)
  raises("pass_through: other has no shape", b.pass_through, b, bare)
  -- called as methods, so that the messages count the arguments as the script wrote them
  raises("bad argument #1 to 'pass_through' (a body of the same world)", function() b:pass_through(foreign) end)
  raises("bad argument #1 to 'pass_through' (rigid.body expected, got number)", function() b:pass_through(1) end)
  raises("bad argument #1 to 'pass_through' (rigid.body expected, got no value)", function() b:pass_through() end)
  raises("rigid.body expected, got rigid.world", b.pass_through, w, b)
  b:pass_through(floor)   -- apart or touching, a valid pair is accepted
  local gone = w:body{ circle = 0.2, x = 3 }
  gone:destroy()
  raises("attempt to use a destroyed body", b.pass_through, b, gone)
  raises("attempt to use a destroyed body", gone.pass_through, gone, b)
end)

-- ---------------------------------------------------------------- contacts

-- At rest the solve cancels what gravity adds in a step: J = m g dt along the normal, no
-- friction; the solver converges on one row to rounding (tolerance: 64 ulps of J).
test("contacts: a resting box has one contact carrying m g dt", function()
  local w, floor = world_with_floor()
  w:set_sleeping(false)
  local b = w:body{ aabb = {0.5, 0.5}, mass = 2, y = 0.5 }
  steps(w, 120)
  local cs = b:contacts()
  eq(#cs, 1, "one contact")
  local c = cs[1]
  check(rawequal(c.other, floor), "the other is the floor's own value")
  near(c.nx, 0, 1e-6, "nx"); near(c.ny, -1, 1e-6, "ny: from the body toward the floor")
  check(c.separation <= 0 and c.separation >= -SLOP, "separation within the slop: " .. c.separation)
  near(c.y, 0, SLOP, "the point is on the floor's top")
  local j = 2 * G * DT
  near(c.normal_impulse, j, 64 * EPS * j, "normal impulse = m g dt")
  near(c.tangent_impulse, 0, 64 * EPS * j, "no friction at rest")
  eq(c.sensor, false)
  local fc = floor:contacts()
  eq(#fc, 1); check(rawequal(fc[1].other, b), "the floor sees the box")
  near(fc[1].ny, 1, 1e-6, "from the floor toward the box")
  near(fc[1].normal_impulse, j, 64 * EPS * j)
end)

-- Pushed with F > mu m g the box slides, and Coulomb friction takes mu * (normal impulse)
-- per step against the motion: on the tangent (-ny, nx) = (1, 0) it reads -mu m g dt.
test("contacts: a box pushed along the floor shows the friction impulse mu m g dt", function()
  local w = world_with_floor()
  local mu = 0.5                                  -- the pair mixes sqrt(0.6 * mu_box)
  local b = w:body{ aabb = {0.5, 0.5}, mass = 2, y = 0.5, friction = mu * mu / 0.6 }
  steps(w, 30)
  for _ = 1, 30 do b:apply_force(25, 0); w:step(DT) end
  check(b:velocity() > 0.5, "sliding")
  local c = b:contacts()[1]
  local j = 2 * G * DT
  near(c.normal_impulse, j, 1e-4 * j, "normal impulse")
  near(c.tangent_impulse, -mu * c.normal_impulse, 1e-4 * j, "friction impulse")
end)

test("contacts: sensors, order by handle, none in the air, bad uses", function()
  local w, floor = world_with_floor()
  local coin = w:body{ type = "static", circle = 0.3, y = 1.5, sensor = true, name = "coin" }
  local tall = w:body{ aabb = {0.5, 1.2}, y = 1.2 }            -- y 0 .. 2.4: crosses the coin
  local top = w:body{ aabb = {0.5, 0.5}, y = 2.9 }
  steps(w, 30)
  local cs = tall:contacts()
  eq(#cs, 3, "floor, coin and the box on top")
  check(rawequal(cs[1].other, floor) and rawequal(cs[2].other, coin) and rawequal(cs[3].other, top),
        "in ascending order of the other's handle (creation order here)")
  eq(cs[2].sensor, true, "the coin is a sensor")
  check(cs[2].normal_impulse == 0 and cs[2].tangent_impulse == 0, "a sensor carries no impulse")
  local air = w:body{ circle = 0.5, x = 15, y = 20 }
  eq(#air:contacts(), 0, "none in the air")
  raises("rigid.body expected, got rigid.world", tall.contacts, w)
  air:destroy()
  raises("attempt to use a destroyed body", air.contacts, air)
  w:close()
  raises("attempt to use a body of a closed world", tall.contacts, tall)
end)

-- ---------------------------------------------------------------- queries

-- Along y = 0 from x = 0 to 10: a box over [1.5, 2.5], a circle r 0.5 at 5 (entered at 4.5),
-- a sensor circle r 0.3 at 7 (entered at 6.7); a box off the path.
local function row()
  local w = rigid.world()
  local box = w:body{ type = "static", aabb = {0.5, 0.5}, x = 2, name = "box" }
  local ball = w:body{ type = "static", circle = 0.5, x = 5, name = "ball" }
  local coin = w:body{ type = "static", circle = 0.3, x = 7, sensor = true, category = 4, name = "coin" }
  w:body{ type = "static", aabb = {0.5, 0.5}, x = 5, y = 5, name = "off" }
  return w, box, ball, coin
end

test("raycast_all: every shape entered, by fraction, the same hits as raycast", function()
  local w, box, ball, coin = row()
  local hits = w:raycast_all(0, 0, 10, 0)
  eq(#hits, 3, "three shapes on the path")
  local want = { { box, 1.5, -1 }, { ball, 4.5, -1 }, { coin, 6.7, -1 } }
  for i, h in ipairs(hits) do
    check(rawequal(h.body, want[i][1]), "hit " .. i .. " is " .. want[i][1]:name())
    near(h.fraction, want[i][2] / 10, 8 * EPS, "fraction " .. i)
    near(h.x, want[i][2], 8 * EPS * 10, "x " .. i); near(h.y, 0, 1e-9, "y " .. i)
    near(h.nx, want[i][3], 1e-6, "nx " .. i); near(h.ny, 0, 1e-6, "ny " .. i)
  end
  local first, x, y, nx, ny, f = w:raycast(0, 0, 10, 0)
  check(rawequal(first, hits[1].body) and x == hits[1].x and y == hits[1].y and nx == hits[1].nx
        and ny == hits[1].ny and f == hits[1].fraction, "raycast's hit is the first of raycast_all")
  eq(#w:raycast_all(0, 0, 10, 0, 1), 2, "mask 1 leaves out the coin (category 4)")
  eq(#w:raycast_all(0, 0, 10, 0, 0), 0, "mask 0 sees nothing")
  eq(#w:raycast_all(2, 0, 10, 0), 2, "a shape containing the origin is not entered")
  eq(#w:raycast_all(0, 3, 10, 0), 0, "nothing on this path")
  raises("finite number expected, got nan", w.raycast_all, w, 0, 0, 0 / 0, 0)
  raises("number expected, got no value", w.raycast_all, w, 0, 0, 1)
  raises("integer in [0, 0xFFFFFFFF] expected", w.raycast_all, w, 0, 0, 1, 0, -1)
  raises("rigid.world expected, got rigid.body", w.raycast_all, box, 0, 0, 1, 0)
end)

test("query_point: shapes containing the point, their boundaries included", function()
  local w = rigid.world()
  local c = w:body{ type = "static", circle = 0.5, name = "circle" }
  local b = w:body{ type = "static", aabb = {1, 0.5}, x = 3, name = "box" }
  local s = w:body{ type = "static", aabb = {1, 1}, x = 3, sensor = true, category = 2 }
  local function at(x, y, mask)
    local names = {}
    for i, body in ipairs(w:query_point(x, y, mask)) do names[i] = body:name() or "sensor" end
    return table.concat(names, ",")
  end
  eq(at(0, 0), "circle", "centre")
  eq(at(0.5, 0), "circle", "on the circle's edge")
  eq(at(0.3, 0.4), "circle", "on the edge off the axes (0.3^2 + 0.4^2 = 0.25)")
  eq(at(0.5 + 1e-4, 0), "", "just outside the circle")
  eq(at(4, 0.5), "box,sensor", "the box's corner, in the sensor too (by handle)")
  eq(at(4, 0.5 + 1e-4), "sensor", "just above the box's corner")
  eq(at(4, 0.5, 1), "box", "mask 1 leaves out the sensor (category 2)")
  check(rawequal(w:query_point(3, 0)[1], b), "the body's own value")
  check(rawequal(w:query_point(3, 0.9)[1], s), "the sensor's own value")
  eq(#w:query_point(0, 0, 0), 0, "mask 0 sees nothing")
  raises("finite number expected, got inf", w.query_point, w, math.huge, 0)
  raises("number expected, got string", w.query_point, w, 0, "0")
  raises("integer in [0, 0xFFFFFFFF] expected", w.query_point, w, 0, 0, 0.5)
  w:close()
  raises("attempt to use a closed world", w.query_point, w, 0, 0)
  check(c, "kept")
end)

test("cast_circle and cast_box: the time of impact of the exact sweep", function()
  local w, box, ball = row()
  -- a circle r 0.25 from x = 0 meets the box's face (1.5) when its centre is at 1.25
  local hit, x, y, nx, ny, f = w:cast_circle(0.25, 0, 0, 10, 0)
  check(rawequal(hit, box), "the box first")
  near(f, 0.125, 8 * EPS, "fraction"); near(x, 1.5, 1e-5, "contact x"); near(y, 0, 1e-6)
  near(nx, -1, 1e-6, "the face's normal, facing the cast"); near(ny, 0, 1e-6)
  -- a box 0.5 x 0.5 whose bottom runs at y = 0.3 meets the circle (r 0.5 at (5, 0)) with its
  -- corner: (cx + 0.25 - 5)^2 + 0.3^2 = 0.5^2 at cx = 4.35; the normal from the circle's
  -- centre to the corner is (-0.4, 0.3) / 0.5
  hit, x, y, nx, ny, f = w:cast_box(0.25, 0.25, 2.6, 0.55, 7.4, 0, 1)
  check(rawequal(hit, ball), "the ball, past the box")
  near(f, (4.35 - 2.6) / 7.4, 1e-5, "fraction of the corner impact")
  near(x, 4.6, 1e-5, "contact x"); near(y, 0.3, 1e-5, "contact y")
  near(nx, -0.8, 1e-5, "nx"); near(ny, 0.6, 1e-5, "ny")
  -- the sensor coin is seen, unless the mask leaves it out
  hit = w:cast_circle(0.1, 6, 0, 3, 0)
  eq(hit:name(), "coin", "sensors included")
  eq(w:cast_circle(0.1, 6, 0, 3, 0, 1), nil, "mask 1 leaves out the coin")
  eq(w:cast_box(0.25, 0.25, 0, 3, 10, 0), nil, "nothing on this path")
end)

test("cast_box: resting on a surface it slides along it, and hits it at 0 going in", function()
  local w, floor = world_with_floor()
  eq(w:cast_box(0.5, 0.5, 0, 0.5 - 0.002, 10, 0), nil, "along the floor, 2 mm into it")
  local hit, _, _, _, ny, f = w:cast_box(0.5, 0.5, 0, 0.5 - 0.002, 0, -1)
  check(rawequal(hit, floor), "down into it: the floor")
  eq(f, 0, "at once"); near(ny, 1, 1e-6, "its top's normal")
end)

test("cast_circle and cast_box: bad arguments raise", function()
  local w = row()
  raises("cast_circle: size.x -1 is below RG_MIN_SHAPE_SIZE", w.cast_circle, w, -1, 0, 0, 1, 0)
  raises("cast_circle: size.x 0 is below RG_MIN_SHAPE_SIZE", w.cast_circle, w, 0, 0, 0, 1, 0)
  raises("cast_box: size.y 0 is below RG_MIN_SHAPE_SIZE", w.cast_box, w, 1, 0, 0, 0, 1, 0)
  raises("finite number expected, got nan", w.cast_circle, w, 0 / 0, 0, 0, 1, 0)
  -- as methods: the messages count the arguments as the script wrote them
  raises("bad argument #5 to 'cast_circle' (finite number expected, got inf)",
         function() w:cast_circle(1, 0, 0, 1, math.huge) end)
  raises("bad argument #6 to 'cast_box' (number expected, got no value)",
         function() w:cast_box(1, 1, 0, 0, 1) end)
  raises("bad argument #6 to 'cast_circle' (integer in [0, 0xFFFFFFFF] expected)",
         function() w:cast_circle(1, 0, 0, 1, 0, 2 ^ 32) end)
  raises("bad argument #7 to 'cast_box' (integer in [0, 0xFFFFFFFF] expected)",
         function() w:cast_box(1, 1, 0, 0, 1, 0, "all") end)
  raises("bad argument #2 to 'raycast_all' (number expected, got no value)", function() w:raycast_all(0) end)
  raises("bad argument #3 to 'query_point' (integer in [0, 0xFFFFFFFF] expected)",
         function() w:query_point(0, 0, -1) end)
  raises("number expected, got string", w.cast_box, w, "1", 1, 0, 0, 1, 0)
  if FLOAT then raises("out of range", w.cast_circle, w, 1e39, 0, 0, 1, 0) end
end)

-- ---------------------------------------------------------------- the mover

-- A floor of 20 flush 1 m tiles (tops at y = 0, x from -10 to 10) and a wall whose left
-- face is at x = 8.
local function room()
  local w = rigid.world{ gravity = {0, -G} }
  for t = 0, 19 do w:body{ type = "static", aabb = {0.5, 0.5}, x = -9.5 + t, y = -0.5, name = "tile" } end
  local wall = w:body{ type = "static", aabb = {0.5, 2}, x = 8.5, y = 2, name = "wall" }
  return w, wall
end

test("move: sliding along the floor into the wall ends flush, at any speed", function()
  for _, reach in ipairs{ 10, 1e3, 1e5 } do
    for _, shape in ipairs{ "aabb", "circle" } do
      local w, wall = room()
      local b = w:body{ type = "kinematic", x = 0, y = 0.5, aabb = shape == "aabb" and {0.25, 0.25} or nil,
                        circle = shape == "circle" and 0.25 or nil }
      local what = ("%s, reach %g"):format(shape, reach)
      local x, y, hits = b:move(reach, -reach / 10)
      local px, py = b:position()
      check(px == x and py == y, what .. ": the position is where it stopped")
      -- flush with the wall (x = 8) and on the floor (y = 0), to rounding
      local tol = 64 * EPS * (1 + reach / 100) + 1e-6
      near(x, 8 - 0.25, tol, what .. ": flush against the wall")
      near(y, 0.25, tol, what .. ": on the floor")
      check(#hits >= 2, what .. ": met the floor and the wall")
      check(rawequal(hits[#hits].body, wall), what .. ": the wall last")
      near(hits[#hits].nx, -1, 1e-6, what .. ": the wall's normal")
      for i = 2, #hits do check(hits[i].fraction >= hits[i - 1].fraction, what .. ": in order") end
      -- nothing overlaps it beyond the slop
      local over = w:query_aabb(x - 0.25 + SLOP, y - 0.25 + SLOP, x + 0.25 - SLOP, y + 0.25 - SLOP)
      check(#over == 1 and rawequal(over[1], b), what .. ": overlaps nothing")
    end
  end
end)

test("move: a box resting on the tile floor slides over the seams without a catch", function()
  local w = room()
  local b = w:body{ aabb = {0.25, 0.25}, x = -9, y = 0.3 }
  steps(w, 60)
  local _, y = b:position()
  check(y <= 0.25 and y >= 0.25 - SLOP, "rests with the solver's slop")
  local x2, y2, hits = b:move(7, y)
  eq(#hits, 0, "no seam is hit"); eq(x2, 7, "the whole way"); eq(y2, y)
end)

test("move: touch stops at the first surface, the velocity untouched", function()
  local w, wall = room()
  local b = w:body{ type = "kinematic", aabb = {0.25, 0.25}, y = 1, vx = 3, vy = 4 }
  -- 2 m down over 10 m to the right: the floor after 0.75 m down, at x = 3.75
  local x, y, hits = b:move(10, -1, { response = "touch" })
  eq(#hits, 1, "one hit")
  near(x, 3.75, 1e-4, "x"); near(y, 0.25, 1e-5, "y")
  near(hits[1].fraction, 0.375, 1e-5, "fraction"); near(hits[1].ny, 1, 1e-6, "the floor's normal")
  eq(hits[1].body:name(), "tile")
  x, y, hits = b:move(100, 0.5, { response = "touch" })
  check(rawequal(hits[1].body, wall), "the wall")
  near(x, 7.75, 1e-5, "flush with the wall")
  local vx, vy = b:velocity()
  eq(vx, 3); eq(vy, 4)
end)

test("move: cross reaches the target and reports every shape crossed, in order", function()
  local w, box, ball, coin = row()
  local m = w:body{ type = "kinematic", aabb = {0.25, 0.25} }
  local x, y, hits = m:move(10, 0, { response = "cross" })
  eq(x, 10); eq(y, 0)
  eq(#hits, 3, "the box, the ball and the coin (a sensor)")
  check(rawequal(hits[1].body, box) and rawequal(hits[2].body, ball) and rawequal(hits[3].body, coin),
        "in the order met")
  near(hits[1].fraction, (2 - 0.5 - 0.25) / 10, 1e-6, "the box's fraction")
  m:set_position(0, 0)
  local _, _, masked = m:move(10, 0, { response = "cross", mask = 1 })
  eq(#masked, 2, "mask 1 leaves out the coin (category 4)")
  m:set_position(6.2, 0)
  local sx, _, slid = m:move(10, 0)
  eq(#slid, 0, "sliding ignores the sensor"); eq(sx, 10)
end)

test("move: a cross through many shapes reports all, and keeps the interpolation", function()
  -- 40 sensors on the path (more than the binding's first buffer holds), one step taken
  -- through the accumulator with alpha 1/2, in which the body went from 0 to 0.2: rendering
  -- blends from where that step started (0), so the interpolated position is halfway from
  -- 0 to wherever it is moved (a teleport back to 0.2 in between would make it 15.1)
  local w = rigid.world{ dt = 0.1 }
  for k = 1, 40 do w:body{ type = "static", circle = 0.1, x = k * 0.5, sensor = true } end
  local m = w:body{ type = "kinematic", circle = 0.1, vx = 2 }
  eq(w:advance(0.15), 1, "one step")
  near(w:alpha(), 0.5, 1e-6, "alpha")
  near(m:position(), 0.2, 1e-6, "moved in the step")
  near(m:interpolated_position(), 0.1, 1e-6, "halfway through the step")
  local x, _, hits = m:move(30, 0, { response = "cross" })
  eq(x, 30); eq(#hits, 40, "every sensor")
  for i = 2, 40 do check(hits[i].fraction > hits[i - 1].fraction, "in order") end
  near(m:interpolated_position(), 15, 1e-5, "halfway from the step's start (0) to 30")
  m:move(40, 0)
  near(m:interpolated_position(), 20, 1e-5, "a slide keeps it too")
end)

test("move: one-way shapes block only against their normal", function()
  local w = rigid.world{ gravity = {0, -G} }
  w:body{ type = "static", aabb = {2, 0.1}, y = 2, one_way = {0, 1} }   -- y 1.9 .. 2.1
  local m = w:body{ type = "kinematic", aabb = {0.25, 0.25} }
  local _, y, hits = m:move(0, 4)
  eq(#hits, 0, "up from below: through"); eq(y, 4)
  _, y, hits = m:move(0, 0)
  eq(#hits, 1, "down from above: lands"); near(y, 2.35, 1e-5, "on top")
  m:set_position(-5, 2)
  _, _, hits = m:move(5, 2)
  eq(#hits, 0, "from the side at its height: through")
end)

test("move: bad arguments raise and change nothing", function()
  local w = room()
  local b = w:body{ type = "kinematic", aabb = {0.25, 0.25}, y = 1 }
  local bare = w:body{ type = "kinematic", y = 3 }
  local bad = {
    { "bad argument #1 to 'move' (finite number expected, got nan)", 0 / 0, 0 },
    { "bad argument #2 to 'move' (finite number expected, got inf)", 0, math.huge },
    { "bad argument #2 to 'move' (number expected, got no value)", 1 },
    { "bad argument #1 to 'move' (number expected, got string)", "1", 0 },
    { "bad argument #3 to 'move' (table expected, got number)", 1, 1, 5 },
    { "move: unknown option 'respons' (known: mask, response)", 1, 1, { respons = "touch" } },
    { "move: option 'response' has no value 'bounce' (slide, touch, cross)", 1, 1, { response = "bounce" } },
    { "move: option 'response' must be a string (got number)", 1, 1, { response = 1 } },
    { "move: option 'mask' must be an integer in [0, 4294967295]", 1, 1, { mask = -1 } },
    { "move: option 'mask' must be an integer (got string)", 1, 1, { mask = "all" } },
  }
  for _, case in ipairs(bad) do
    raises(case[1], function() b:move(unpack(case, 2)) end)   -- as a method: #1 is tx
    local x, y = b:position()
    check(x == 0 and y == 1, case[1] .. ": changed nothing")
  end
  raises("move: body has no shape", bare.move, bare, 1, 1)
  if FLOAT then
    raises("out of range", b.move, b, 1e39, 0)
    -- a target whose distance overflows rg_real
    raises("move: target.x 3e+38 is above RG_MAX_COORD", b.move, b, 3e38, -3e38)
  end
  raises("rigid.body expected, got rigid.world", b.move, w, 1, 1)
  local x, y = b:position()
  check(x == 0 and y == 1, "nothing was moved")
  b:destroy()
  raises("attempt to use a destroyed body", b.move, b, 1, 1)
end)

-- ---------------------------------------------------------------- every new method

test("destroyed bodies and closed worlds: every gameplay method raises", function()
  local w, floor = world_with_floor()
  local b = w:body{ circle = 0.2 }
  b:destroy()
  for _, u in ipairs{ { "set_one_way", 0, 1 }, { "one_way" }, { "contacts" }, { "move", 1, 1 },
                      { "pass_through", floor } } do
    raises("attempt to use a destroyed body", b[u[1]], b, unpack(u, 2))
  end
  local live = w:body{ circle = 0.2, x = 2 }
  w:close()
  for _, u in ipairs{ { "set_one_way", 0, 1 }, { "one_way" }, { "contacts" }, { "move", 1, 1 },
                      { "pass_through", floor } } do
    raises("attempt to use a body of a closed world", live[u[1]], live, unpack(u, 2))
  end
  for _, u in ipairs{ { "raycast_all", 0, 0, 1, 0 }, { "query_point", 0, 0 },
                      { "cast_circle", 1, 0, 0, 1, 0 }, { "cast_box", 1, 1, 0, 0, 1, 0 } } do
    raises("attempt to use a closed world", w[u[1]], w, unpack(u, 2))
  end
end)

print(passed .. " passed, " .. failed .. " failed")
if failed > 0 then error(failed .. " Lua test(s) failed", 0) end
