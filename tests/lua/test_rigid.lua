-- test_rigid.lua: the Lua API of rigid.  Runs in the sandboxed host (build/rigid), in
-- stock lua5.4 with LUA_CPATH="build/?.so", and in LuaJIT through the FFI binding
-- (LUA_PATH="lua/?.lua;;" RIGID_LIBRARY=build/librigid.so luajit ...): one API, one script.
-- The sandbox section runs only in the host, the Lua 5.4 syntax (<close>) and the host's
-- own library functions only in Lua 5.4.  Prints "N passed, N failed" and fails when
-- anything failed.
local rigid = require(jit and "rigid_jit" or "rigid")
local unpack = table.unpack or unpack

local passed, failed = 0, 0
local current

local function test(name, f)
  current = name
  local ok, err = pcall(f)
  if ok then
    passed = passed + 1
  else
    failed = failed + 1
    print("FAIL " .. name .. ": " .. tostring(err))
  end
end

local function check(cond, what)
  if not cond then error(what or "check failed", 2) end
end

local function eq(a, b, what)
  if a ~= b then
    error(string.format("%s: expected %s, got %s", what or "value", tostring(b), tostring(a)), 2)
  end
end

local function near(a, b, tol, what)
  if type(a) ~= "number" or math.abs(a - b) > tol then
    error(string.format("%s: expected %.9g (+-%g), got %s", what or "value", b, tol, tostring(a)), 2)
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
local TOL = FLOAT and 1e-4 or 1e-9      -- relative tolerance for a few hundred steps
local sandboxed = io == nil

-- ---------------------------------------------------------------- module

test("module: version, real size, collision flag", function()
  check(type(rigid.version) == "string" and rigid.version:match("^%d+%.%d+%.%d+$"), "version")
  check(rigid.real_size == 4 or rigid.real_size == 8, "real_size")
  eq(type(rigid.collision), "boolean", "collision flag")
  eq(type(rigid.world), "function", "rigid.world")
end)

-- ---------------------------------------------------------------- worlds

test("world: defaults", function()
  local w = rigid.world()
  local gx, gy = w:gravity()
  eq(gx, 0, "gravity x"); eq(gy, 0, "gravity y")
  local wx, wy = w:wind()
  eq(wx, 0, "wind x"); eq(wy, 0, "wind y")
  eq(w:integrator(), "semi_implicit", "integrator")
  local dt, max = w:fixed_step()
  near(dt, 1 / 60, 1e-7, "dt"); eq(max, 8, "max steps")
  eq(w:body_count(), 0, "bodies"); eq(w:spring_count(), 0, "springs")
  check(w:is_open(), "open")
  check(tostring(w):find("rigid.world (0 bodies, 0 springs)", 1, true), tostring(w))
end)

test("world: options", function()
  local w = rigid.world{ gravity = {1, -9.81}, wind = {2, 3}, integrator = "rk4", dt = 0.01, max_steps = 3 }
  local gx, gy = w:gravity()
  near(gx, 1, 1e-6); near(gy, -9.81, 1e-5)
  local wx, wy = w:wind()
  eq(wx, 2); eq(wy, 3)
  eq(w:integrator(), "rk4")
  local dt, max = w:fixed_step()
  near(dt, 0.01, 1e-8); eq(max, 3)
end)

test("world: setters and getters", function()
  local w = rigid.world()
  w:set_gravity(0, -3); local _, gy = w:gravity(); eq(gy, -3)
  w:set_wind(-1, 0); local wx = w:wind(); eq(wx, -1)
  for _, name in ipairs{ "explicit", "semi_implicit", "verlet", "rk4" } do
    w:set_integrator(name); eq(w:integrator(), name)
  end
  w:set_fixed_step(1 / 30, 4)
  local dt, max = w:fixed_step(); near(dt, 1 / 30, 1e-7); eq(max, 4)
  w:set_fixed_step(1 / 50)
  dt, max = w:fixed_step(); near(dt, 1 / 50, 1e-7); eq(max, 4, "max kept")
end)

test("world: close, __close and use after close", function()
  local w = rigid.world()
  local b = w:body{}
  w:close()
  check(not w:is_open(), "closed")
  eq(tostring(w), "rigid.world (closed)")
  raises("attempt to use a closed world", w.step, w, 1 / 60)
  raises("attempt to use a closed world", w.body, w, {})
  raises("attempt to use a body of a closed world", b.position, b)
  check(not b:is_valid(), "body of a closed world is not valid")
  eq(b:destroy(), false, "destroy in a closed world")
  w:close()   -- twice is fine
end)

-- To-be-closed variables are Lua 5.4 syntax, which LuaJIT does not parse: this chunk is
-- compiled only there.
if _VERSION == "Lua 5.4" then
  assert(load([[
    local rigid, test, check, eq = ...
    test("world: __close closes at the end of the scope", function()
      local kept
      do
        local w2 <close> = rigid.world()
        kept = w2
        check(kept:is_open(), "open inside the scope")
      end
      check(not kept:is_open(), "closed at the end of the scope")
    end)

    test("body: __close destroys at the end of the scope", function()
      local w = rigid.world()
      local kept
      do
        local b <close> = w:body{}
        kept = b
        eq(w:body_count(), 1)
      end
      eq(w:body_count(), 0); check(not kept:is_valid())
    end)
  ]], "=test_rigid.lua (Lua 5.4 syntax)"))(rigid, test, check, eq)
end

-- ---------------------------------------------------------------- bodies

test("body: defaults", function()
  local w = rigid.world()
  local b = w:body()
  eq(b:type(), "dynamic"); eq(b:mass(), 1)
  local x, y = b:position(); eq(x, 0); eq(y, 0)
  local vx, vy = b:velocity(); eq(vx, 0); eq(vy, 0)
  eq(b:user_data(), 0); eq(b:name(), nil)
  eq(b:gravity_scale(), 1)
  local lin, quad = b:drag(); eq(lin, 0); eq(quad, 0)
  local lo, hi = b:speed_limits(); eq(lo, 0); eq(hi, 0)
  check(b:is_valid()); eq(b:world(), w)
  eq(w:body_count(), 1)
  check(tostring(b):match("^rigid%.body #%d+ %(dynamic%)$"), tostring(b))
end)

test("body: options", function()
  local w = rigid.world()
  local b = w:body{ type = "dynamic", mass = 2.5, x = 1, y = 2, vx = 3, vy = -4, gravity_scale = 0.5,
                    drag = {0.1, 0.2}, surface_friction = {0.3, 1}, min_speed = 0.01, max_speed = 100,
                    user_data = 42, name = "hero" }
  eq(b:mass(), 2.5)
  local x, y = b:position(); eq(x, 1); eq(y, 2)
  local vx, vy = b:velocity(); eq(vx, 3); eq(vy, -4)
  eq(b:user_data(), 42); eq(b:name(), "hero")
  -- read back as the library stores them: an rg_real (float: within half an ulp, 2^-24 of it)
  local ulp = rigid.real_size == 4 and 2 ^ -24 or 0
  eq(b:gravity_scale(), 0.5)
  local lin, quad = b:drag(); near(lin, 0.1, 0.1 * ulp); near(quad, 0.2, 0.2 * ulp)
  local lo, hi = b:speed_limits(); near(lo, 0.01, 0.01 * ulp); eq(hi, 100)
  b:set_speed_limits(0.5); lo, hi = b:speed_limits(); eq(lo, 0.5); eq(hi, 0)
  check(tostring(b):find('"hero" (dynamic)', 1, true), tostring(b))
  local s = w:body{ type = "static", x = 5, mass = 123 }
  eq(s:type(), "static"); eq(s:mass(), 0)
  local k = w:body{ type = "kinematic", vx = 2 }
  eq(k:type(), "kinematic")
  w:step(0.5)
  local kx = k:position(); near(kx, 1, 1e-6, "kinematic moves by its velocity")
  local sx = s:position(); eq(sx, 5, "static stays")
end)

test("body: free fall matches the semi-implicit Euler closed form", function()
  local w = rigid.world{ gravity = {0, -9.81} }
  local b = w:body{ y = 100 }
  local dt, n = 1 / 60, 120
  for _ = 1, n do w:step(dt) end
  local _, y = b:position()
  local _, vy = b:velocity()
  near(vy, -9.81 * n * dt, 1e-3, "vy")
  near(y, 100 - 9.81 * dt * dt * n * (n + 1) / 2, 100 * TOL, "y")
end)

test("body: forces last one step, impulses act at once", function()
  local w = rigid.world()
  local b = w:body{ mass = 2 }
  b:apply_force(4, 0)
  w:step(0.1)
  local vx = b:velocity(); near(vx, 0.2, 1e-6, "v after the force")
  local x = b:position(); near(x, 0.02, 1e-6, "x")
  w:step(0.1)
  vx = b:velocity(); near(vx, 0.2, 1e-6, "the force was cleared")
  local ax = b:acceleration(); eq(ax, 0, "no acceleration without the force")
  b:apply_impulse(0, 2)
  local _, vy = b:velocity(); near(vy, 1, 1e-6, "impulse / mass")
  b:set_velocity(-1, 0); vx = b:velocity(); eq(vx, -1)
  b:set_position(7, 8); local px, py = b:position(); eq(px, 7); eq(py, 8)
  b:set_mass(4); eq(b:mass(), 4)
  local s = w:body{ type = "static" }
  s:apply_force(100, 0); w:step(0.1)
  eq(s:position(), 0, "a static body ignores forces")
end)

-- Many calls in a row (under LuaJIT the loop runs as compiled code, through its own
-- declarations of the vector calls): every value set is read back exactly.  The values
-- are multiples of 1/4 below 2^10, exact in a float.
test("body: set_position and set_velocity read back exactly, 2000 times", function()
  local w = rigid.world()
  local b = w:body{}
  local wrong = 0
  for i = 1, 2000 do
    b:set_position(i * 0.25, -i * 0.5)
    b:set_velocity(-i * 0.25, i * 0.125)
    local x, y = b:position()
    local vx, vy = b:velocity()
    if x ~= i * 0.25 or y ~= -i * 0.5 or vx ~= -i * 0.25 or vy ~= i * 0.125 then wrong = wrong + 1 end
  end
  eq(wrong, 0, "calls that read back another value")
  b:set_position(0, 0); b:set_velocity(0, 0)
  for _ = 1, 2000 do b:apply_force(3, -1) end   -- forces add up over one step
  w:step(0.5)
  local vx, vy = b:velocity()
  eq(vx, 2000 * 3 * 0.5, "vx = sum(F) dt / m"); eq(vy, -2000 * 0.5, "vy = sum(F) dt / m")
end)

test("body: gravity scale", function()
  local w = rigid.world{ gravity = {0, -10} }
  local floats = w:body{ gravity_scale = 0 }
  local rises = w:body{}
  rises:set_gravity_scale(-1)
  for _ = 1, 10 do w:step(0.1) end
  local _, y0 = floats:position(); eq(y0, 0)
  local _, y1 = rises:position(); check(y1 > 5, "falls up: " .. y1)
end)

test("body: quadratic drag reaches terminal speed sqrt(m g / k)", function()
  local w = rigid.world{ gravity = {0, -9.81} }
  local b = w:body{ mass = 1, drag = {0, 0.5} }
  for _ = 1, 600 do w:step(1 / 60) end
  local _, vy = b:velocity()
  near(vy, -math.sqrt(9.81 / 0.5), 0.01 * math.sqrt(9.81 / 0.5), "terminal speed")
  b:set_drag(0, 0)
  raises("set_drag: linear -1 is not >= 0", b.set_drag, b, -1)
end)

test("body: surface friction stops a slide at v^2 / (2 mu g)", function()
  local w = rigid.world()
  local b = w:body{ mass = 2, vx = 5 }
  b:set_surface_friction(0.5, 2 * 9.81)
  for _ = 1, 240 do w:step(1 / 60) end
  local vx = b:velocity(); eq(vx, 0, "at rest, exactly")
  -- Discretely: n = floor(v0 / (a dt)) steps of x += (v0 - k a dt) dt, which is the
  -- continuous v0^2 / (2 a) less about v0 dt / 2.
  local a, dt = 0.5 * 9.81, 1 / 60
  local n = math.floor(5 / (a * dt))
  local x = b:position()
  near(x, dt * (n * 5 - a * dt * n * (n + 1) / 2), 1e-3, "stopping distance")
  near(x, 25 / (2 * a), 5 * dt / 2 + 1e-3, "close to the continuous distance")
  raises("set_surface_friction: mu -1 is not >= 0", b.set_surface_friction, b, -1, 1)
end)

test("body: speed limits", function()
  local w = rigid.world{ gravity = {0, -10} }
  local b = w:body{ max_speed = 3 }
  for _ = 1, 60 do w:step(1 / 60) end
  local vx, vy = b:velocity(); near(math.sqrt(vx * vx + vy * vy), 3, 1e-4, "clamped")
  local slow = w:body{ vx = 0.3, gravity_scale = 0 }
  slow:set_speed_limits(0.5)
  w:step(1 / 60)
  eq(slow:velocity(), 0, "snapped to rest below min_speed")
  raises("set_speed_limits: max_speed 1 is below min_speed 2", b.set_speed_limits, b, 2, 1)
  raises("set_speed_limits: min_speed -1 is not >= 0", b.set_speed_limits, b, -1)
end)

test("body: user data and name", function()
  local w = rigid.world()
  local b = w:body{ name = "crate" }
  b:set_user_data(-7); eq(b:user_data(), -7)
  raises("number has no integer representation", b.set_user_data, b, 0.5)
  -- all 64 bits (in LuaJIT, values past 2^53 come back as int64_t cdata, equal to them)
  b:set_user_data(2 ^ 62); check(b:user_data() == 2 ^ 62, "2^62")
  b:set_user_data(-2 ^ 63); check(b:user_data() == -2 ^ 63, "-2^63")
  raises("number has no integer representation", b.set_user_data, b, 2 ^ 63)
  eq(w:body{ user_data = -2 ^ 63 }:user_data() == -2 ^ 63, true, "option user_data -2^63")
  eq(b:name(), "crate")
  -- an integer; in LuaJIT, whose numbers cannot hold 64 bits, an int64_t cdata
  local id = b:id()
  check((type(id) == "number" or jit and type(id) == "cdata") and id ~= 0, "id")
  eq(b:id(), id, "the same id each time")
end)

test("body: mass rules", function()
  local w = rigid.world()
  local b = w:body{}
  raises("set_mass: mass 0 is below RG_MIN_MASS (1e-06)", b.set_mass, b, 0)
  raises("set_mass: mass -2 is below RG_MIN_MASS (1e-06)", b.set_mass, b, -2)
  local s = w:body{ type = "static" }
  raises("set_mass: body is not dynamic (only a dynamic body has a mass)", s.set_mass, s, 1)
  raises("set_velocity: velocity (1, 0) of a static body is not 0", s.set_velocity, s, 1, 0)
end)

test("body: bad arguments raise for every method", function()
  local w = rigid.world()
  local b = w:body{}
  local two = { "set_position", "set_velocity", "apply_force", "apply_impulse", "set_surface_friction" }
  for _, m in ipairs(two) do
    raises("number expected, got no value", b[m], b)
    raises("number expected, got no value", b[m], b, 1)
    raises("number expected, got string", b[m], b, "1", 1)
    raises("number expected, got table", b[m], b, 1, {})
    raises("finite number expected, got nan", b[m], b, 0 / 0, 1)
    raises("finite number expected, got inf", b[m], b, 1, math.huge)
    raises("finite number expected, got inf", b[m], b, -math.huge, 1)
    if FLOAT then raises("out of range", b[m], b, 1e300, 1) end
  end
  for _, m in ipairs{ "set_mass", "set_gravity_scale", "set_drag", "set_speed_limits" } do
    raises("number expected, got no value", b[m], b)
    raises("finite number expected, got nan", b[m], b, 0 / 0)
    raises("number expected, got boolean", b[m], b, true)
  end
  local methods = { "position", "velocity", "apply_force", "set_position", "mass", "destroy",
                    "is_valid", "type", "name", "id", "world" }
  for _, m in ipairs(methods) do
    raises("rigid.body expected, got rigid.world", b[m], w)
    raises("rigid.body expected, got nil", b[m], nil)
    raises("rigid.body expected, got table", b[m], {})
  end
  eq(select("#", b:position()), 2, "nothing was changed")
  local x, y = b:position(); eq(x, 0); eq(y, 0)
end)

test("body: metatable is protected", function()
  local w = rigid.world()
  local b = w:body{}
  eq(getmetatable(b), "rigid.body")
  eq(getmetatable(w), "rigid.world")
end)

test("body: destroy, then every use raises", function()
  local w = rigid.world()
  local b = w:body{ name = "gone" }
  local other = w:body{}
  eq(b:destroy(), true); eq(b:destroy(), false, "second destroy is a no-op")
  check(not b:is_valid())
  eq(w:body_count(), 1)
  check(tostring(b):find("(destroyed)", 1, true), tostring(b))
  local uses = {
    { "position" }, { "velocity" }, { "set_position", 1, 1 }, { "set_velocity", 1, 1 },
    { "apply_force", 1, 0 }, { "apply_impulse", 1, 0 }, { "interpolated_position" },
    { "acceleration" }, { "type" }, { "mass" }, { "set_mass", 2 }, { "set_gravity_scale", 1 },
    { "set_drag", 0, 0 }, { "set_surface_friction", 0, 0 }, { "set_speed_limits", 0, 0 },
    { "user_data" }, { "set_user_data", 1 },
  }
  if rigid.collision then
    for _, u in ipairs{ { "grounded" }, { "set_circle", 1 }, { "set_aabb", 1, 1 },
                        { "set_restitution", 0 }, { "set_friction", 0 }, { "set_sensor", true },
                        { "set_filter", 1, 1 }, { "clear_shape" }, { "is_awake" }, { "wake" } } do
      uses[#uses + 1] = u
    end
  end
  for _, u in ipairs(uses) do
    raises("attempt to use a destroyed body", b[u[1]], b, unpack(u, 2))
  end
  eq(b:name(), "gone", "the name stays readable")
  raises("attempt to use a destroyed body", w.spring, w, { a = b, b = other, stiffness = 1 })
  local bodies = w:bodies()
  eq(#bodies, 1); eq(bodies[1], other)
end)

test("body: identity across world:bodies(), tables keyed by body, garbage collection", function()
  local w = rigid.world()
  local a, b, c = w:body{ name = "a" }, w:body{ name = "b" }, w:body{ name = "c" }
  local score = { [a] = 1, [b] = 2, [c] = 3 }
  local list = w:bodies()
  eq(#list, 3)
  eq(list[1], a); eq(list[2], b); eq(list[3], c)
  check(rawequal(list[2], b), "the same value, not an equal one")
  eq(score[list[3]], 3)
  -- A body nobody holds lives on in its world and keeps its value.
  w:body{ name = "dropped", x = 9 }
  collectgarbage(); collectgarbage()
  list = w:bodies()
  eq(#list, 4); eq(list[4]:name(), "dropped")
  eq(list[4]:position(), 9)
  eq(list[1]:world(), w)
  check(a == list[1] and a ~= b, "__eq")
end)

test("body: a world stays alive while its bodies are held", function()
  local b
  do
    local w = rigid.world{ gravity = {0, -1} }
    b = w:body{}
  end
  collectgarbage(); collectgarbage()
  local w = b:world()
  check(w:is_open(), "world kept alive by its body")
  w:step(1)
  local _, vy = b:velocity(); eq(vy, -1)
end)

-- ---------------------------------------------------------------- stepping

test("advance: fixed steps, the cap, alpha and interpolation", function()
  local w = rigid.world{ dt = 0.1, max_steps = 3 }
  local b = w:body{ vx = 1 }
  eq(w:advance(0.25), 2, "two whole steps")
  near(w:alpha(), 0.5, 1e-5, "alpha")
  local x = b:position(); near(x, 0.2, 1e-6)
  local ix = b:interpolated_position(); near(ix, 0.15, 1e-6, "halfway between the last two")
  eq(w:advance(10), 3, "capped")
  eq(w:advance(0), 0)
  w:step(0.1)
  local ix2 = b:interpolated_position(); local x2 = b:position()
  eq(ix2, x2, "after a direct step, the current position")
end)

test("integrators: all four reach free fall within tolerance", function()
  for _, name in ipairs{ "explicit", "semi_implicit", "verlet", "rk4" } do
    local w = rigid.world{ gravity = {0, -10}, integrator = name }
    local b = w:body{}
    for _ = 1, 100 do w:step(0.01) end
    local _, y = b:position()
    near(y, -5, 0.06, name)
  end
end)

-- ---------------------------------------------------------------- springs

test("springs: anchor and two-body springs, destroy and counting", function()
  local w = rigid.world()
  local b = w:body{ x = 2 }
  local s = w:spring{ a = b, anchor = {0, 0}, stiffness = 4 }
  eq(w:spring_count(), 1); check(s:is_valid())
  check(tostring(s):find("live", 1, true))
  local maxx, minx = 0, 0
  for _ = 1, 400 do
    w:step(1 / 120)
    local x = b:position()
    maxx = math.max(maxx, x); minx = math.min(minx, x)
  end
  check(minx < -1.9 and maxx <= 2.01, "oscillates within its amplitude: " .. minx .. " " .. maxx)
  eq(s:destroy(), true); eq(s:destroy(), false); check(not s:is_valid())
  local c = w:body{ x = 1 }
  local s2 = w:spring{ a = b, b = c, rest_length = 1, stiffness = 10, damping = 0.5 }
  check(s2:is_valid())
  c:destroy()
  check(not s2:is_valid(), "destroying a body destroys its springs")
  eq(w:spring_count(), 0)
end)

-- The range guard: 1e12 N (RG_MAX_FORCE) on 1e-6 kg (RG_MIN_MASS) for 10 s (RG_MAX_DT) would
-- reach 1e19 m/s and 1e20 m; the step stops the body at x = 1e9 (RG_MAX_COORD) and lists it
-- until the next stepping call.
test("stopped: a body driven out of range stops at the edge and is listed", function()
  local w = rigid.world()
  local calm = w:body{ x = 5 }
  local b = w:body{ mass = 1e-6 }
  b:apply_force(1e12, 0)
  w:step(10)
  local list = w:stopped()
  eq(#list, 1, "stopped count"); check(rawequal(list[1], b), "the body's own value")
  local x, y = b:position()
  eq(x, 1e9, "x at the edge"); eq(y, 0, "y")
  local vx, vy = b:velocity()
  eq(vx, 0, "vx"); eq(vy, 0, "vy")
  eq(calm:position(), 5, "the body in range is untouched")
  w:step(10)
  eq(#w:stopped(), 0, "cleared by the next step")
  w:close()
  raises("attempt to use a closed world", w.stopped, w)
end)

-- ---------------------------------------------------------------- collision

if rigid.collision then
  test("collision: shapes, materials, filters from options and setters", function()
    local w = rigid.world()
    local b = w:body{ circle = 0.5, restitution = 0.5, friction = 0.2, sensor = false,
                      category = 2, mask = 0xFFFFFFFF }
    local c = w:body{ aabb = {1, 0.5} }
    b:set_aabb(0.3, 0.3); b:set_circle(0.25); b:set_restitution(1); b:set_friction(0)
    b:set_sensor(true); b:set_sensor(false); b:set_filter(4, 0xF)
    c:clear_shape()
    raises("options 'circle' and 'aabb' exclude each other", w.body, w, { circle = 1, aabb = {1, 1} })
    raises("world:body: option 'circle': radius -1 is below RG_MIN_SHAPE_SIZE (1e-06)", w.body, w,
           { circle = -1 })
    raises("world:body: option 'aabb': half_height 0 is below RG_MIN_SHAPE_SIZE", w.body, w,
           { aabb = {1, 0} })
    raises("world:body: option 'restitution': restitution 2 is above 1", w.body, w,
           { circle = 1, restitution = 2 })
    raises("world:body: option 'friction': mu -1 is not >= 0", w.body, w, { circle = 1, friction = -1 })
    raises("option 'sensor' must be a boolean", w.body, w, { sensor = 1 })
    raises("option 'category' must be an integer in [0, 4294967295]", w.body, w, { category = -1 })
    raises("option 'mask' must be an integer", w.body, w, { mask = 0.5 })
    raises("set_circle: radius 0 is below RG_MIN_SHAPE_SIZE (1e-06)", b.set_circle, b, 0)
    raises("set_aabb: half_height -1 is below RG_MIN_SHAPE_SIZE", b.set_aabb, b, 1, -1)
    raises("set_restitution: restitution -0.1 is not >= 0", b.set_restitution, b, -0.1)
    raises("boolean expected", b.set_sensor, b, 1)
    raises("integer in [0, 0xFFFFFFFF] expected", b.set_filter, b, 2 ^ 32, 1)
    eq(w:body_count(), 2, "failed creations left nothing")
  end)

  -- A ball dropped on the ground: begin then end events, the same values as the bodies.
  local function drop_scene()
    local w = rigid.world{ gravity = {0, -10} }
    local ground = w:body{ type = "static", aabb = {10, 0.5}, y = -0.5, name = "ground" }
    local ball = w:body{ circle = 0.5, y = 2, restitution = 0.5, name = "ball" }
    return w, ground, ball
  end

  test("events: begin with identity, fields, and grounded", function()
    local w, ground, ball = drop_scene()
    local seen
    for _ = 1, 120 do
      w:step(1 / 60)
      for _, e in ipairs(w:events()) do
        if e.kind == "begin" and not seen then seen = e end
      end
      if seen then break end
    end
    check(seen, "a begin event")
    check(rawequal(seen.a, ground) or rawequal(seen.a, ball), "event bodies are the same values")
    check((seen.a == ground and seen.b == ball) or (seen.a == ball and seen.b == ground), "the pair")
    local keyed = { [ground] = "g", [ball] = "b" }
    check(keyed[seen.a] and keyed[seen.b], "usable as table keys")
    near(math.sqrt(seen.nx ^ 2 + seen.ny ^ 2), 1, 1e-4, "unit normal")
    check(seen.speed > 1, "approach speed " .. seen.speed)
    eq(seen.sensor, false)
    check(seen.depth >= 0, "depth")
    for _ = 1, 240 do w:step(1 / 60) end
    check(ball:grounded(), "resting on the ground")
    check(not ground:grounded(), "static bodies are never grounded")
    local _, y = ball:position(); near(y, 0.5, 0.05, "rests on top")
  end)

  test("events: destroying bodies while iterating is safe", function()
    local w = rigid.world{ gravity = {0, -10} }
    w:body{ type = "static", aabb = {10, 0.5}, y = -0.5 }
    local balls = {}
    for i = 1, 5 do balls[i] = w:body{ circle = 0.2, x = i - 3, y = 0.3 } end
    local destroyed, ends = 0, 0
    for _ = 1, 30 do
      w:step(1 / 60)
      for _, e in ipairs(w:events()) do
        if e.kind == "begin" then
          for _, body in ipairs{ e.a, e.b } do
            if body:type() ~= "static" and body:is_valid() then
              body:destroy(); destroyed = destroyed + 1
            end
          end
          check(not e.a:is_valid() or not e.b:is_valid(), "one side is gone")
        else
          ends = ends + 1
        end
      end
    end
    eq(destroyed, 5, "every ball met the ground")
    eq(w:body_count(), 1)
    check(ends >= 5, "end events for destroyed bodies: " .. ends)
  end)

  test("events: an end event names a destroyed body by the value scripts hold", function()
    local w, ground, ball = drop_scene()
    local began
    for _ = 1, 120 do
      w:step(1 / 60)
      for _, e in ipairs(w:events()) do if e.kind == "begin" then began = true end end
      if began then break end
    end
    check(began, "touching")
    ball:destroy()
    w:step(1 / 60)
    local found
    for _, e in ipairs(w:events()) do
      if e.kind == "end" then found = e end
    end
    check(found, "an end event after the destroy")
    check(rawequal(found.a, ball) or rawequal(found.b, ball), "the destroyed body's own value")
    check(rawequal(found.a, ground) or rawequal(found.b, ground), "and the ground")
  end)

  test("events: one advance of several steps reports the events of all of them", function()
    -- a coin pickup on a slow frame: the ball (0.1 m a step) enters a 4 cm sensor in the
    -- first of four steps and leaves it in the fourth
    local w = rigid.world{ dt = 1 / 60, max_steps = 8 }
    local coin = w:body{ type = "static", aabb = {0.02, 1}, sensor = true }
    local ball = w:body{ circle = 0.1, x = -0.2, vx = 6 }
    eq(w:advance(4.5 / 60), 4, "four steps")
    local ev = w:events()
    eq(#ev, 2, "both events")
    eq(ev[1].kind, "begin"); eq(ev[2].kind, "end")
    for _, e in ipairs(ev) do
      check((e.a == coin and e.b == ball) or (e.a == ball and e.b == coin), "the pair")
    end
    eq(w:advance(0), 0)
    eq(#w:events(), 0, "no step, no events")
  end)

  test("sensors report, never push; filters", function()
    local w = rigid.world{ gravity = {0, -10} }
    local zone = w:body{ type = "static", aabb = {1, 1}, sensor = true, name = "zone" }
    local ball = w:body{ circle = 0.2, y = 3 }
    local ghost = w:body{ circle = 0.2, y = 3, x = 0.1, category = 2, mask = 2 }
    local sensed = {}
    for _ = 1, 60 do
      w:step(1 / 60)
      for _, e in ipairs(w:events()) do
        if e.sensor and e.kind == "begin" then
          sensed[e.a == zone and e.b or e.a] = true
        end
      end
    end
    check(sensed[ball], "the ball entered the zone")
    check(not sensed[ghost], "the filtered body did not")
    local _, y = ball:position()
    check(y < -1, "fell through the sensor: " .. y)
  end)

  test("raycast and query_aabb return the same values", function()
    local w, ground, ball = drop_scene()
    local hit, hx, hy, nx, ny, frac = w:raycast(0, 10, 0, -20)
    check(rawequal(hit, ball), "the ball is hit first")
    near(hy, 2.5, 1e-4); eq(hx, 0); near(ny, 1, 1e-4); eq(nx, 0); near(frac, 0.375, 1e-4)
    local h2 = w:raycast(5, 10, 0, -20)
    check(rawequal(h2, ground), "the ground elsewhere")
    eq(w:raycast(50, 10, 0, -1), nil, "nothing")
    eq(w:raycast(0, 10, 0, -20, 0), nil, "mask 0 sees nothing")
    local found = w:query_aabb(-1, 1, 1, 3)
    eq(#found, 1); check(rawequal(found[1], ball))
    eq(#w:query_aabb(-20, -20, 20, 20), 2)
    raises("query_aabb: lower (1, 1) is not <= upper (0, 0)", w.query_aabb, w, 1, 1, 0, 0)
    raises("finite number expected", w.raycast, w, 0 / 0, 0, 1, 1)
  end)

  test("sleeping, waking and world settings", function()
    local w = rigid.world{ gravity = {0, -10} }
    w:body{ type = "static", aabb = {10, 0.5}, y = -0.5 }
    local box = w:body{ aabb = {0.5, 0.5}, y = 0.5 }
    w:set_sleeping(true)
    for _ = 1, 120 do w:step(1 / 60) end
    check(not box:is_awake(), "asleep at rest")
    box:wake(); check(box:is_awake(), "woken")
    w:set_solver_iterations(8, 2)
    w:set_continuous(false); w:set_continuous(true)
    raises("boolean expected", w.set_sleeping, w, 1)
    raises("set_solver_iterations: velocity 0 is not in 1..64", w.set_solver_iterations, w, 0, 0)
  end)

  test("solver iterations: the C defaults, position kept when omitted", function()
    local w = rigid.world()
    local v, p = w:solver_iterations()
    eq(v, 8, "velocity default (rigid.h)"); eq(p, 3, "position default (rigid.h)")
    w:set_solver_iterations(12)
    v, p = w:solver_iterations()
    eq(v, 12, "velocity set"); eq(p, 3, "position kept")
    w:set_solver_iterations(4, 0)
    w:set_solver_iterations(6)
    v, p = w:solver_iterations()
    eq(v, 6, "velocity set again"); eq(p, 0, "a position of 0 kept too")
    raises("set_solver_iterations: velocity 65 is not in 1..64", w.set_solver_iterations, w, 65)
    raises("set_solver_iterations: position -1 is not in 0..64", w.set_solver_iterations, w, 8, -1)
    raises("number has no integer representation", w.set_solver_iterations, w, 1.5)
    v, p = w:solver_iterations()
    eq(v, 6, "a refused call changes nothing"); eq(p, 0, "a refused call changes nothing")
  end)
end

-- ---------------------------------------------------------------- the sandbox (host only)

if sandboxed then
  test("sandbox: no io, os (but clock and time), package, debug, files", function()
    eq(io, nil); eq(package, nil); eq(debug, nil); eq(dofile, nil); eq(loadfile, nil)
    eq(type(os.clock), "function"); eq(type(os.time), "function")
    eq(os.execute, nil); eq(os.exit, nil); eq(os.getenv, nil); eq(os.remove, nil); eq(os.rename, nil)
    eq(string.dump, nil)
  end)

  test("sandbox: load takes text only, with its env", function()
    eq(load("return 1 + 1")(), 2)
    eq(load("return x", "chunk", "t", { x = 5 })(), 5)
    eq(load("return 3", "chunk", "b")(), 3, "mode is forced to text")
    local parts = { "return ", "4" }
    local i = 0
    eq(load(function() i = i + 1; return parts[i] end)(), 4, "reader function")
    local f, err = load("\27Lua\84\0\25\147\13\10\26\10")
    eq(f, nil); check(err:find("binary chunk", 1, true), err)
    local g, err2 = load("return +")
    eq(g, nil); check(err2:find("unexpected symbol", 1, true), err2)
  end)

  test("sandbox: no finalizers (Lua runs them with hooks off)", function()
    raises("__gc metamethods are not available in the sandbox", setmetatable, {}, { __gc = print })
    local t = setmetatable({}, { __index = { x = 1 } })
    eq(t.x, 1, "other metatables are fine")
    eq(setmetatable(t, nil), t)
  end)

  test("sandbox: require gives rigid and nothing else", function()
    eq(require "rigid", rigid)
    raises("module 'io' is not available in the sandbox", require, "io")
    raises("module 'os' is not available in the sandbox", require, "os")
  end)

  test("sandbox: bounded library functions keep their meaning", function()
    eq(string.rep("", math.maxinteger), "", "an empty repeat is immediate")
    eq(string.rep("", 10, ""), "")
    eq(string.rep("ab", 3, ","), "ab,ab,ab")
    eq(("x"):rep(0), "")
    raises("resulting string too large", string.rep, "xx", math.maxinteger)
    raises("would not fit in the memory cap", string.rep, "x", 2 ^ 40)
    -- The doubling copy against a plain concatenation, at every count up to 40 (the partial
    -- last copy falls at each offset) with and without a separator, empty pieces included.
    for _, piece in ipairs({ { "", "," }, { "a", "" }, { "ab", "" }, { "abc", "-+" }, { "", "xy" } }) do
      for n = 0, 40 do
        local want = ""
        for i = 1, n do want = want .. (i > 1 and piece[2] or "") .. piece[1] end
        eq(string.rep(piece[1], n, piece[2]), want, "rep(" .. piece[1] .. ", " .. n .. ", " .. piece[2] .. ")")
      end
    end
    -- the charged wrappers keep stock Lua's results and argument errors, names included
    eq(string.format("%5.2f|%s|%d|%q", 3.14159, "abc", 42, "a\nb"), " 3.14|abc|42|\"a\\\nb\"")
    eq(table.concat({ 1, 2.5, "x" }, ","), "1,2.5,x")
    eq(table.concat({ 1, 2, 3 }, "-", 2, 3), "2-3")
    raises("bad argument #2 to 'string.format' (number expected, got string)", string.format, "%d", "x")
    raises("bad argument #1 to 'table.sort' (table expected, got number)", table.sort, 5)
    raises("bad argument #1 to 'select' (number expected, got string)", select, "x")
    raises("invalid value (table) at index 1 in table for 'concat'", table.concat, { {} })
    raises("invalid value (nil) at index 1 in table for 'concat'", table.concat, {}, "", 1, math.maxinteger)
    eq(select(2, string.unpack("<i4", string.pack("<i4", -7))), 5)
    eq(string.unpack("<i4", string.pack("<i4", -7)), -7)
    eq(string.packsize("i4i8"), 12)
    eq(type(collectgarbage("count")), "number")
    eq(collectgarbage(), 0)
    eq(("hello world"):find("o w"), 5)
    eq(("key=val"):match("(%w+)=(%w+)"), "key")
    eq(("a,b,c"):gsub(",", ";"), "a;b;c")
    local words = {}
    for w in ("one two"):gmatch("%a+") do words[#words + 1] = w end
    eq(table.concat(words, "|"), "one|two")
  end)
end

-- coroutine.create/wrap and xpcall are the host's own (budget-aware) versions: the same
-- meaning as stock Lua's, checked in both (not in LuaJIT, whose libraries are its own).
if not jit then
  test("coroutines and xpcall", function()
    local gen = coroutine.wrap(function(a)
      local b = coroutine.yield(a + 1)
      coroutine.yield(b * 2)
      return "done"
    end)
    eq(gen(1), 2); eq(gen(5), 10); eq(gen(), "done")
    raises("cannot resume dead coroutine", gen)
    local failing = coroutine.wrap(function() error("inside") end)
    raises("inside", failing)
    local co = coroutine.create(function(x) return x * 3 end)
    local ok, v = coroutine.resume(co, 4)
    check(ok and v == 12, "resume"); eq(coroutine.status(co), "dead")
    raises("function expected", coroutine.create, 1)
    raises("function expected", coroutine.wrap, nil)
    local seen
    local ok2, msg = xpcall(function() error("boom", 0) end, function(m) seen = m; return "handled " .. m end)
    check(not ok2 and msg == "handled boom" and seen == "boom", "xpcall calls its handler")
    local a, b, c = xpcall(function(x, y) return x + y, "second" end, print, 2, 3)
    check(a == true and b == 5 and c == "second", "xpcall passes arguments and results")
    -- A yield inside xpcall inside a coroutine works (the host's xpcall is yieldable).
    local y = coroutine.wrap(function()
      return xpcall(function() return coroutine.yield("paused") + 1 end, print)
    end)
    eq(y(), "paused")
    local r1, r2 = y(41)
    check(r1 == true and r2 == 42, "resumed inside xpcall")
    raises("bad argument #2 to 'xpcall'", xpcall, print)
  end)

  -- table.insert/remove/move: the same meaning in the host (its own versions) and in stock Lua.
  test("table functions", function()
    local t = { 1, 2, 3 }
    table.insert(t, 4); table.insert(t, 1, 0)
    eq(table.concat(t, ","), "0,1,2,3,4")
    eq(table.remove(t), 4); eq(table.remove(t, 1), 0)
    eq(table.concat(t, ","), "1,2,3")
    raises("position out of bounds", table.insert, t, 9, 1)
    raises("wrong number of arguments to 'insert'", table.insert, t, 1, 2, 3)
    local m = table.move({ 1, 2, 3 }, 1, 3, 2)
    eq(table.concat(m, ","), "1,1,2,3")
    local d = table.move({ 1, 2, 3 }, 1, 3, 1, {})
    eq(table.concat(d, ","), "1,2,3")
    eq(table.remove({}), nil)
  end)
end

print(passed .. " passed, " .. failed .. " failed")
if failed > 0 then error(failed .. " Lua test(s) failed", 0) end
