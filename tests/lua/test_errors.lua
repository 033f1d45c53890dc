-- test_errors.lua: the error messages of the Lua API.  A failed library call raises the
-- Lua call's name and the library's reason (rg_world_last_error: the argument, its value
-- and the rule it broke, with the header's constant); checks the binding makes itself
-- (types, option names, enum values) say what was expected.  Runs where
-- tests/lua/test_rigid.lua runs: in the sandboxed host, in stock lua5.4 and in LuaJIT
-- through lua/rigid_jit.lua, so both bindings give the same messages.  (Its few helpers
-- repeat test_rigid.lua's: the sandbox loads no second file.)  Prints "N passed, N failed"
-- and fails when anything failed.
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

local function eq(a, b, what)
  if a ~= b then error(("%s: expected %s, got %s"):format(what or "value", tostring(b), tostring(a)), 2) end
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

-- Each case { message, f, arguments... }: f(...) raises exactly that message (nothing before
-- it but a position, nothing after it), and the call changes nothing that check() reads.
local function messages(cases, check)
  for _, case in ipairs(cases) do
    local before = check and check()
    local ok, err = pcall(case[2], unpack(case, 3, case.n or #case))
    err = tostring(err)
    if ok then error("no error, expected: " .. case[1], 2) end
    local before_text = err:sub(1, -#case[1] - 1)
    if err:sub(-#case[1]) ~= case[1] or not (before_text == "" or before_text:match("^[^ ]+:%d+: $")) then
      error(("expected: %s\n      got: %s"):format(case[1], err), 2)
    end
    if check and check() ~= before then error("the failed call changed something: " .. case[1], 2) end
  end
end

-- ---------------------------------------------------------------- the library's reasons

test("body: the message names the call, the argument and the rule", function()
  local w = rigid.world()
  local b, s = w:body{ x = 1 }, w:body{ type = "static" }
  local function state()
    local x, y = b:position()
    local vx, vy = b:velocity()
    return ("%a %a %a %a %a"):format(x, y, vx, vy, b:mass())
  end
  messages({
    { "set_mass: mass 0 is below RG_MIN_MASS (1e-06)", b.set_mass, b, 0 },
    { "set_mass: mass 1e+30 is above RG_MAX_MASS (1e+09)", b.set_mass, b, 1e30 },
    { "set_mass: body is not dynamic (only a dynamic body has a mass)", s.set_mass, s, 1 },
    { "set_velocity: velocity (1, 0) of a static body is not 0", s.set_velocity, s, 1, 0 },
    { "set_position: position.x 1e+30 is above RG_MAX_COORD (1e+09)", b.set_position, b, 1e30, 0 },
    { "apply_impulse: impulse.x 1e+30 is above RG_MAX_FORCE (1e+12)", b.apply_impulse, b, 1e30, 0 },
    { "apply_force: force.x 1e+30 is above RG_MAX_FORCE (1e+12)", b.apply_force, b, 1e30, 0 },
    { "set_gravity_scale: scale 1e+09 is above RG_MAX_GRAVITY_SCALE (1000)", b.set_gravity_scale, b, 1e9 },
    { "set_drag: linear -1 is not >= 0", b.set_drag, b, -1 },
    { "set_drag: quadratic -1 is not >= 0", b.set_drag, b, 0, -1 },
    { "set_surface_friction: mu -1 is not >= 0", b.set_surface_friction, b, -1, 1 },
    { "set_surface_friction: normal_force -1 is not >= 0", b.set_surface_friction, b, 0.5, -1 },
    { "set_speed_limits: min_speed -1 is not >= 0", b.set_speed_limits, b, -1 },
    { "set_speed_limits: max_speed -1 is not >= 0", b.set_speed_limits, b, 0, -1 },
    { "set_speed_limits: max_speed 1 is below min_speed 2 (and not 0: no limit)", b.set_speed_limits, b, 2, 1 },
    { "world:body: mass 0 is below RG_MIN_MASS (1e-06)", w.body, w, { mass = 0 } },
    { "world:body: option 'vx/vy': velocity (1, 0) of a static body is not 0", w.body, w,
      { type = "static", vx = 1 } },
    { "world:body: option 'gravity_scale': scale -2000 is below -RG_MAX_GRAVITY_SCALE (-1000)", w.body, w,
      { gravity_scale = -2000 } },
  }, state)
  eq(w:body_count(), 2, "world:body left nothing behind")
end)

test("shape: the message names the call, the argument and the rule", function()
  local w = rigid.world()
  local c = w:body{ circle = 1 }
  local function state()
    local kind, a, b = c:shape()
    return ("%s %s %s %a %a %s"):format(kind, a, tostring(b), c:restitution(), c:friction(), tostring(c:is_sensor()))
  end
  messages({
    { "set_circle: radius 0 is below RG_MIN_SHAPE_SIZE (1e-06)", c.set_circle, c, 0 },
    { "set_circle: radius 1e+08 is above RG_MAX_SHAPE_SIZE (1e+07)", c.set_circle, c, 1e8 },
    { "set_aabb: half_width 0 is below RG_MIN_SHAPE_SIZE (1e-06)", c.set_aabb, c, 0, 1 },
    { "set_aabb: half_height 1e+08 is above RG_MAX_SHAPE_SIZE (1e+07)", c.set_aabb, c, 1, 1e8 },
    { "set_restitution: restitution 2 is above 1", c.set_restitution, c, 2 },
    { "set_friction: mu -1 is not >= 0", c.set_friction, c, -1 },
    { "set_friction: mu 1e+09 is above RG_MAX_FRICTION (1000)", c.set_friction, c, 1e9 },
    { "set_one_way: normal (0.5, 0) has length 0.5, not 1 (within 1e-3) nor 0", c.set_one_way, c, 0.5, 0 },
    { "world:body: option 'circle': radius -1 is below RG_MIN_SHAPE_SIZE (1e-06)", w.body, w, { circle = -1 } },
    { "world:body: option 'aabb': half_height 0 is below RG_MIN_SHAPE_SIZE (1e-06)", w.body, w,
      { aabb = {1, 0} } },
    { "world:body: option 'restitution': restitution 2 is above 1", w.body, w,
      { circle = 1, restitution = 2 } },
  }, state)
  eq(w:body_count(), 1, "world:body left nothing behind")
end)

test("world: the message names the call, the argument and the rule", function()
  local w = rigid.world()
  local function state()
    local gx, gy = w:gravity()
    local dt, max = w:fixed_step()
    local v, p = w:solver_iterations()
    return ("%a %a %a %d %d %d"):format(gx, gy, dt, max, v, p)
  end
  messages({
    { "step: dt 0 is not > 0", w.step, w, 0 },
    { "advance: frame_time -1 is not >= 0", w.advance, w, -1 },
    { "set_gravity: gravity.x 1e+30 is above RG_MAX_ACCELERATION (1e+06)", w.set_gravity, w, 1e30, 0 },
    { "set_wind: force.y 1e+30 is above RG_MAX_FORCE (1e+12)", w.set_wind, w, 0, 1e30 },
    { "set_fixed_step: dt 1e+09 is above RG_MAX_DT (10)", w.set_fixed_step, w, 1e9 },
    { "set_sleep_thresholds: speed -1 is not >= 0", w.set_sleep_thresholds, w, -1, 1 },
    { "set_sleep_thresholds: time 0 is not > 0", w.set_sleep_thresholds, w, 1, 0 },
    { "set_solver_iterations: velocity 65 is not in 1..64", w.set_solver_iterations, w, 65 },
    { "set_solver_iterations: position -1 is not in 0..64", w.set_solver_iterations, w, 8, -1 },
    { "set_contact_tuning: slop -1 is not >= 0", w.set_contact_tuning, w, -1, 0.5, 1, 1 },
    { "set_contact_tuning: bias_rate 2 is above 1", w.set_contact_tuning, w, 0, 2, 1, 1 },
    { "set_contact_tuning: max_push 0 is not > 0", w.set_contact_tuning, w, 0, 0.5, 0, 1 },
    { "set_contact_tuning: restitution_threshold -1 is not >= 0", w.set_contact_tuning, w, 0, 0.5, 1, -1 },
    { "rigid.world: option 'gravity': gravity.x 1e+30 is above RG_MAX_ACCELERATION (1e+06)",
      rigid.world, { gravity = {1e30, 0} } },
    { "rigid.world: option 'wind': force.y 1e+30 is above RG_MAX_FORCE (1e+12)", rigid.world,
      { wind = {0, 1e30} } },
    { "rigid.world: option 'dt': dt 0 is not > 0", rigid.world, { dt = 0 } },
  }, state)
end)

test("spring: the message names the call, the argument and the rule", function()
  local w = rigid.world()
  local a, b = w:body{}, w:body{ x = 1 }
  messages({
    { "world:spring: b is a (a spring joins two bodies)", w.spring, w, { a = a, b = a, stiffness = 1 } },
    { "world:spring: stiffness -1 is not >= 0", w.spring, w, { a = a, b = b, stiffness = -1 } },
    { "world:spring: damping -1 is not >= 0", w.spring, w, { a = a, b = b, stiffness = 1, damping = -1 } },
    { "world:spring: rest_length -1 is not >= 0", w.spring, w,
      { a = a, b = b, stiffness = 1, rest_length = -1 } },
    { "world:spring: anchor.x 1e+30 is above RG_MAX_COORD (1e+09)", w.spring, w,
      { a = a, anchor = {1e30, 0}, stiffness = 1 } },
  }, function() return w:spring_count() end)
end)

test("query: the message names the call, the argument and the rule", function()
  local w = rigid.world()
  local c, bare = w:body{ circle = 1 }, w:body{ x = 3 }
  messages({
    { "query_aabb: lower (1, 1) is not <= upper (0, 0)", w.query_aabb, w, 1, 1, 0, 0 },
    { "query_aabb: upper.x 1e+30 is above RG_MAX_QUERY_COORD (1e+12)", w.query_aabb, w, 0, 0, 1e30, 1 },
    { "raycast: origin.x 1e+30 is above RG_MAX_QUERY_COORD (1e+12)", w.raycast, w, 1e30, 0, 1, 0 },
    { "raycast: translation.x 1e+30 is above RG_MAX_QUERY_COORD (1e+12)", w.raycast, w, 0, 0, 1e30, 0 },
    { "raycast_all: origin.y 1e+30 is above RG_MAX_QUERY_COORD (1e+12)", w.raycast_all, w, 0, 1e30, 1, 0 },
    { "query_point: point.x 1e+30 is above RG_MAX_QUERY_COORD (1e+12)", w.query_point, w, 1e30, 0 },
    { "cast_circle: size.x 0 is below RG_MIN_SHAPE_SIZE (1e-06)", w.cast_circle, w, 0, 0, 0, 1, 0 },
    { "cast_box: size.x 1e+08 is above RG_MAX_SHAPE_SIZE (1e+07)", w.cast_box, w, 1e8, 1, 0, 0, 1, 0 },
    { "pass_through: other is body (a pair is two bodies)", c.pass_through, c, c },
    { "pass_through: other has no shape", c.pass_through, c, bare },
    { "move: body has no shape", bare.move, bare, 1, 1 },
    { "move: target.x 1e+30 is above RG_MAX_COORD (1e+09)", c.move, c, 1e30, 0 },
  }, function() local x, y = c:position() return ("%a %a"):format(x, y) end)
end)

test("the binding's own checks stay its own: types, ranges of integers, destroyed bodies", function()
  local w = rigid.world()
  local b = w:body{}
  messages({
    { "bad argument #1 to 'set_circle' (number expected, got string)", function() b:set_circle("1") end },
    { "bad argument #2 to 'set_fixed_step' (max_steps must be >= 1)", function() w:set_fixed_step(1 / 60, 0) end },
    { "bad argument #1 to 'set_integrator' (invalid integrator 'euler' (explicit, semi_implicit, verlet, rk4))",
      function() w:set_integrator("euler") end },
    { "world:body: unknown option 'mas' (known: type, mass, x, y, vx, vy, gravity_scale, drag, " ..
      "surface_friction, min_speed, max_speed, user_data, name, circle, aabb, restitution, friction, " ..
      "sensor, category, mask, one_way)", w.body, w, { mas = 1 } },
    { "world:body: options 'circle' and 'aabb' exclude each other", w.body, w, { circle = 1, aabb = {1, 1} } },
  })
  b:destroy()
  messages({ { "attempt to use a destroyed body", b.set_circle, b, 1 } })
end)

-- ---------------------------------------------------------------- option tables and arguments

test("world: bad options raise and name the option", function()
  raises("unknown option 'gravty'", rigid.world, { gravty = {0, -1} })
  raises("option names must be strings", rigid.world, { 1 })
  raises("option 'gravity' must be a table", rigid.world, { gravity = 5 })
  raises("two numbers", rigid.world, { gravity = {0} })
  raises("two numbers", rigid.world, { gravity = {0, 1, 2} })
  raises("item 2 is a string", rigid.world, { gravity = {0, "down"} })
  raises("finite", rigid.world, { gravity = {0, 0 / 0} })
  raises("finite", rigid.world, { wind = {math.huge, 0} })
  raises("has no value 'euler'", rigid.world, { integrator = "euler" })
  raises("rigid.world: option 'dt': dt 0 is not > 0", rigid.world, { dt = 0 })
  raises("rigid.world: option 'dt': dt -1 is not > 0", rigid.world, { dt = -1 })
  raises("max_steps", rigid.world, { max_steps = 0 })
  raises("max_steps", rigid.world, { max_steps = 1.5 })
  raises("table expected", rigid.world, 5)
end)

test("world: bad arguments raise", function()
  local w = rigid.world()
  raises("number expected, got string", w.set_gravity, w, "0", 1)
  raises("number expected, got no value", w.set_gravity, w, 0)
  raises("finite number expected, got nan", w.set_gravity, w, 0 / 0, 0)
  raises("finite number expected, got inf", w.set_wind, w, 0, -math.huge)
  raises("invalid integrator 'euler'", w.set_integrator, w, "euler")
  raises("string expected", w.set_integrator, w, 1)
  raises("step: dt 0 is not > 0", w.step, w, 0)
  raises("step: dt -1 is not > 0", w.step, w, -1)
  raises("finite number expected", w.step, w, 0 / 0)
  raises("number expected, got string", w.step, w, "1")
  raises("advance: frame_time -1 is not >= 0", w.advance, w, -1)
  raises("set_fixed_step: dt 0 is not > 0", w.set_fixed_step, w, 0)
  raises("max_steps must be >= 1", w.set_fixed_step, w, 1 / 60, 0)
  raises("number has no integer representation", w.set_fixed_step, w, 1 / 60, 1.5)
  raises("rigid.world expected, got nil", w.step, nil, 1)
  raises("rigid.world expected, got table", w.step, {}, 1)
  local b = w:body{}
  raises("rigid.world expected, got rigid.body", w.step, b, 1 / 60)
  if FLOAT then raises("out of range", w.set_gravity, w, 1e39, 0) end
end)

test("enum options and arguments list the valid values", function()
  local w = rigid.world()
  raises("option 'type' has no value 'Dynamic' (static, kinematic, dynamic)", w.body, w,
         { type = "Dynamic" })
  raises("option 'integrator' has no value 'rk5' (explicit, semi_implicit, verlet, rk4)",
         rigid.world, { integrator = "rk5" })
  raises("invalid integrator 'Verlet' (explicit, semi_implicit, verlet, rk4)",
         w.set_integrator, w, "Verlet")
  eq(w:integrator(), "semi_implicit", "a refused name changes nothing")
  eq(w:body_count(), 0, "a refused type creates nothing")
end)

test("body: bad options raise, name the option and create nothing", function()
  local w = rigid.world()
  raises("unknown option 'mas'", w.body, w, { mas = 1 })
  raises("known: type, mass", w.body, w, { mas = 1 })
  raises("option names must be strings", w.body, w, { 1, 2 })
  raises("option 'mass' must be a number (got string)", w.body, w, { mass = "heavy" })
  raises("option 'mass' must be a finite number", w.body, w, { mass = 0 / 0 })
  raises("option 'x' must be a finite number", w.body, w, { x = math.huge })
  raises("option 'type' has no value 'rock'", w.body, w, { type = "rock" })
  raises("option 'type' must be a string", w.body, w, { type = 2 })
  raises("world:body: mass 0 is below RG_MIN_MASS (1e-06)", w.body, w, { mass = 0 })
  raises("world:body: mass -1 is below RG_MIN_MASS (1e-06)", w.body, w, { mass = -1 })
  raises("world:body: option 'vx/vy': velocity (1, 0) of a static body is not 0", w.body, w,
         { type = "static", vx = 1 })
  raises("world:body: option 'drag': linear -1 is not >= 0", w.body, w, { drag = {-1, 0} })
  raises("two numbers", w.body, w, { drag = {1} })
  raises("(it has key ", w.body, w, { drag = { x = 1, y = 2 } })
  raises("world:body: option 'surface_friction': mu -0.5 is not >= 0", w.body, w,
         { surface_friction = {-0.5, 1} })
  raises("world:body: option 'min_speed/max_speed': max_speed 1 is below min_speed 2", w.body, w,
         { min_speed = 2, max_speed = 1 })
  raises("option 'name' must be a string", w.body, w, { name = 5 })
  raises("option 'user_data' must be an integer", w.body, w, { user_data = 1.5 })
  raises("table expected, got string", w.body, w, "ball")
  eq(w:body_count(), 0, "no body was left behind")
  if FLOAT then raises("finite number", w.body, w, { y = 1e39 }) end
end)

test("springs: bad options raise", function()
  local w, w2 = rigid.world(), rigid.world()
  local a, b = w:body{}, w:body{}
  local foreign = w2:body{}
  raises("option 'a' (a body) is required", w.spring, w, { stiffness = 1, anchor = {0, 0} })
  raises("option 'stiffness' is required", w.spring, w, { a = a, b = b })
  raises("option 'anchor' {x, y} is required", w.spring, w, { a = a, stiffness = 1 })
  raises("option 'a' must be a body", w.spring, w, { a = 1, stiffness = 1, anchor = {0, 0} })
  raises("body of another world", w.spring, w, { a = a, b = foreign, stiffness = 1 })
  raises("unknown option 'k'", w.spring, w, { a = a, b = b, k = 1 })
  raises("world:spring: b is a (a spring joins two bodies)", w.spring, w, { a = a, b = a, stiffness = 1 })
  raises("world:spring: stiffness -1 is not >= 0", w.spring, w, { a = a, b = b, stiffness = -1 })
  raises("finite", w.spring, w, { a = a, b = b, stiffness = 0 / 0 })
  eq(w:spring_count(), 0)
end)

-- ---------------------------------------------------------------- where an error points

-- The message f(...) raises when a function of this file calls it, and the position of that
-- call: error(_, 2) from pcall, on the same line, names the line as luaL_error does.
local function raised_from_here(f, ...)
  local args = { n = select("#", ...), ... }
  local here, err
  local _, e = pcall(function() here = select(2, pcall(error, "", 2)); f(unpack(args, 1, args.n)) end)
  err = tostring(e)
  return err, here
end

test("an error points at the script line that called, whichever way the binding failed", function()
  local w = rigid.world()
  local b = w:body{ circle = 0.5 }
  b:destroy()
  for _, case in ipairs{
    -- the library refused a destroyed body's handle (position and velocity: their fast
    -- path failed, then the getter said why; LuaJIT lost the line until 2026-12-07)
    { "attempt to use a destroyed body", b.position, b },
    { "attempt to use a destroyed body", b.velocity, b },
    { "attempt to use a destroyed body", b.set_circle, b, 1 },
    { "attempt to use a destroyed body", b.contacts, b },
    { "attempt to use a destroyed body", b.move, b, 1, 1 },
    -- the library refused a query's bounds (query_aabb and query_point, as above)
    { "query_aabb: lower (1, 1) is not <= upper (0, 0)", w.query_aabb, w, 1, 1, 0, 0 },
    { "query_point: point.x 1e+30 is above RG_MAX_QUERY_COORD (1e+12)", w.query_point, w, 1e30, 0 },
    { "raycast: origin.x 1e+30 is above RG_MAX_QUERY_COORD (1e+12)", w.raycast, w, 1e30, 0, 1, 0 },
    -- the binding's own checks (of options: a bad argument's number depends on the call's
    -- form, a method's or a function's)
    { "world:body: option 'x' must be a finite number (got nan)", w.body, w, { x = 0 / 0 } },
    { "world:body: option 'aabb' must hold finite numbers (item 2 is nan)", w.body, w, { aabb = { 1, 0 / 0 } } },
  } do
    local err, here = raised_from_here(unpack(case, 2))
    if not here:match("^[^ ]+:%d+: $") then error("not a line's position: " .. here) end
    eq(err, here .. case[1], "the message")
  end
end)

test("a method a script calls by a tail call names itself and counts as a method", function()
  local w = rigid.world()
  local b = w:body{ circle = 0.5 }
  local function tail(r) return b:set_circle(r) end
  local function tail_world(i) return w:set_solver_iterations(i) end
  for _, case in ipairs{
    { "bad argument #1 to 'set_circle' (number expected, got string)", tail, "1" },
    { "bad argument #1 to 'set_solver_iterations' (number expected, got boolean)", tail_world, true },
  } do
    local ok, err = pcall(case[2], case[3])
    err = tostring(err)
    -- Lua 5.4 names the tail call's line; LuaJIT has no frame left to name
    if ok or not (err == case[1] or err:match("^[^ ]+:%d+: (.*)$") == case[1]) then
      error(("expected: %s\n      got: %s"):format(case[1], err))
    end
  end
end)


print(passed .. " passed, " .. failed .. " failed")
if failed > 0 then error(failed .. " Lua test(s) failed", 0) end
