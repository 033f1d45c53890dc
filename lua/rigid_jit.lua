-- rigid_jit.lua: the LuaJIT (and LOVE) binding of rigid, through the FFI, with the API of
-- the Lua 5.4 module: every function, option, event field and error message that the top
-- comment of lua/lrigid.c lists.  `local rigid = require "rigid_jit"`.
--
-- Its parts: rigid_jit/ffi.lua loads the library (RIGID_LIBRARY, else librigid) and
-- declares the header; rigid_jit/check.lua checks arguments and words the errors;
-- rigid_jit/query.lua has the events and queries of a world, rigid_jit/contact.lua a body's
-- contacts, passing through and moving, rigid_jit/snapshot.lua world:save, world:restore
-- and world:hash (as lua/lquery.c, lua/lcontact.c and lua/lsnapshot.c).
-- Bodies, worlds and springs are tables with a protected metatable.  A body is one value
-- wherever it appears (world:body, world:bodies, events, queries), so tables can be keyed
-- by it, also after it is destroyed, for as long as anyone holds it; a world stays alive
-- while any of its bodies is held.  Where LuaJIT has no 64-bit integers, body:id(),
-- world:hash() and a large body:user_data() are int64_t cdata, and user data may be given
-- as such cdata.
local ffi = require "ffi"
local lib = require "rigid_jit.ffi"
local check = require "rigid_jit.check"

local C, V = lib.C, lib.V
local raise, argerror, typeerror, status_error = check.raise, check.argerror, check.typeerror,
                                                 check.status_error
local real1, real2, real4, optreal = check.real1, check.real2, check.real4, check.optreal
local option_names, option_real, option_pair = check.option_names, check.option_real,
                                               check.option_pair
local option_integer, option_enum, option_error = check.option_integer, check.option_enum,
                                                  check.option_error
local WORLD, BODY, SPRING = check.WORLD, check.BODY, check.SPRING
local INTEGRATORS, TYPES = check.INTEGRATORS, check.TYPES
local PUBLIC = check.PUBLIC

local vec = ffi.new("rg_vec2[1]")
-- Vectors read back come in a fresh out-struct per call: with the one shared buffer above,
-- LuaJIT 2.1.0-beta3's JIT (Debian's) now and then compared values read from it across the
-- calls of a trace stale (2 test runs in 40 saw a body's position unequal to an equal one;
-- never with -joff, never with a fresh struct).  It costs some 15 ns a call.
local vec2_out = ffi.typeof("rg_vec2[1]")
local real = ffi.new("rg_real[2]")
local i32 = ffi.new("int32_t[2]")
local u32 = ffi.new("uint32_t[2]")
local u64 = ffi.new("uint64_t[1]")
local wptr = ffi.new("rg_world *[1]")
local INT64, UINT64 = ffi.typeof("int64_t"), ffi.typeof("uint64_t")

-- A 64-bit integer as Lua 5.4 shows it (signed): a number when that is exact.
local function int64(u)
  local s = ffi.cast(INT64, u)
  if s >= -2 ^ 53 and s <= 2 ^ 53 then return tonumber(s) end
  return s
end

-- ---------------------------------------------------------------- objects
--
-- A world is { box, live, dead, next serial, springs }.  box, a struct rigid_jit_world,
-- holds the rg_world pointer (NULL once closed) and destroys the library world when it is
-- collected, which is once neither the world value nor any of its bodies is held.  live
-- maps handle keys to the bodies created through Lua (strongly: a body lives in its world
-- whether or not a script holds it); dead maps destroyed ones, weakly; springs maps handle
-- keys to spring values, weakly.
-- A body is { box, handle, world, serial, type, name, retired }; a spring { box, handle,
-- world, retired }.  retired is true for a value destroyed for good because a restore took
-- the world back to before it was made and the world gave its handle out again (as
-- lua/lbody.c and lua/lspring.c).  The library checks every handle, so a table that poses
-- as one of these can only name bodies of a world that is still open.
local W_BOX, W_LIVE, W_DEAD, W_SERIAL, W_SPRINGS = 1, 2, 3, 4, 5
local B_BOX, B_H, B_WORLD, B_SERIAL, B_TYPE, B_NAME, B_RETIRED = 1, 2, 3, 4, 5, 6, 7
local S_RETIRED = 4
local World, Body, Spring = {}, {}, {}
local world_mt = { __index = World, __metatable = WORLD }
local body_mt = { __index = Body, __metatable = BODY }
local spring_mt = { __index = Spring, __metatable = SPRING }

local function world_destroy(box)
  if box.w ~= nil then C.rg_world_destroy(box.w) end
  box.w = nil
end

-- The 8 bytes of a handle: a table key that tells every handle apart.
local function hkey(h)
  u64[0] = h
  return ffi.string(u64, 8)
end

local function check_world(w)
  if getmetatable(w) ~= WORLD then typeerror(1, WORLD, w) end
  return w[W_BOX]
end

local function open_world(w)
  local p = check_world(w).w
  if p == nil then raise("attempt to use a closed world") end
  return p
end

local function check_body(b)
  if getmetatable(b) ~= BODY then typeerror(1, BODY, b) end
  return b
end

-- The world pointer and handle of body b.
local function body_wh(b)
  if getmetatable(b) ~= BODY then typeerror(1, BODY, b) end
  local p = b[B_BOX].w
  if p == nil then raise("attempt to use a body of a closed world") end
  if b[B_RETIRED] then raise("attempt to use a destroyed body") end
  return p, b[B_H]
end

-- The handle of body b given as an argument (checked as body_wh does).
local function body_handle(b)
  local _, h = body_wh(b)
  return h
end

local function new_body(world, h, type_, serial, name)
  return setmetatable({ world[W_BOX], h, world, serial, type_, name }, body_mt)
end

-- The body value for handle h of world: the one scripts hold, or a new one.
local function push_body(world, h)
  local key = hkey(h)
  local b = world[W_LIVE][key] or world[W_DEAD][key]
  if b then return b end
  local p = world[W_BOX].w
  local type_ = p ~= nil and C.rg_body_get_type(p, h, i32) == 0 and i32[0] or -1
  b = new_body(world, h, type_, 0, nil)
  world[W_DEAD][key] = b
  return b
end

-- ---------------------------------------------------------------- worlds

local WORLD_OPTIONS = { "gravity", "wind", "integrator", "dt", "max_steps" }

local function new_world(...)
  local what, opts = "rigid.world", ...
  local gx, gy, wx, wy, integrator, dt, max_steps
  if opts ~= nil then
    check.checktable(1, opts, true)
    option_names(opts, WORLD_OPTIONS, what)
    gx, gy = option_pair(opts, "gravity", what)
    wx, wy = option_pair(opts, "wind", what)
    integrator = option_enum(opts, "integrator", what, INTEGRATORS)
    dt = option_real(opts, "dt", what)
    max_steps = option_integer(opts, "max_steps", what, 1, 0x7FFFFFFF)
  end
  local box = ffi.gc(ffi.new("struct rigid_jit_world"), world_destroy)
  local st = C.rg_world_create(wptr)
  if st ~= 0 then status_error(nil, st, what) end
  local p, failed = wptr[0], nil
  box.w = p
  if st == 0 and gx then st, failed = V.rg_world_set_gravity(p, gx, gy), "gravity" end
  if st == 0 and wx then st, failed = V.rg_world_set_wind(p, wx, wy), "wind" end
  if st == 0 and integrator then st, failed = C.rg_world_set_integrator(p, integrator), "integrator" end
  if st == 0 and (dt or max_steps) then
    st, failed = C.rg_world_get_fixed_step(p, real, i32), dt and "dt" or "max_steps"
    if st == 0 then st = C.rg_world_set_fixed_step(p, dt or real[0], max_steps or i32[0]) end
  end
  if st ~= 0 then
    local why = check.reason(p, st)   -- before the destroy frees it
    world_destroy(box)
    raise(("%s: option '%s': %s"):format(what, failed, why))
  end
  return setmetatable({ box, {}, setmetatable({}, { __mode = "v" }), 1,
                        setmetatable({}, { __mode = "v" }) }, world_mt)
end

function World.close(w) world_destroy(check_world(w)) end
function World.is_open(w) return check_world(w).w ~= nil end
world_mt.__close = World.close

function world_mt.__tostring(w)
  local p = check_world(w).w
  if p == nil then return "rigid.world (closed)" end
  return ("rigid.world (%d bodies, %d springs)"):format(C.rg_world_body_count(p),
                                                       C.rg_world_spring_count(p))
end

function World.step(w, ...)
  local p = open_world(w)
  local st = C.rg_world_step(p, real1(2, ...))
  if st ~= 0 then status_error(p, st, "step") end
end

function World.advance(w, ...)
  local p = open_world(w)
  local st = C.rg_world_advance(p, real1(2, ...), i32)
  if st ~= 0 then status_error(p, st, "advance") end
  return i32[0]
end

function World.alpha(w)
  local p = open_world(w)
  local st = C.rg_world_get_alpha(p, real)
  if st ~= 0 then status_error(p, st, "alpha") end
  return real[0]
end

function World.fixed_step(w)
  local p = open_world(w)
  local st = C.rg_world_get_fixed_step(p, real, i32)
  if st ~= 0 then status_error(p, st, "fixed_step") end
  return real[0], i32[0]
end

function World.set_fixed_step(w, ...)
  local p = open_world(w)
  local dt, max = real1(2, ...), select(2, ...)
  local st = C.rg_world_get_fixed_step(p, real, i32)
  if st ~= 0 then status_error(p, st, "set_fixed_step") end
  max = max == nil and i32[0] or check.checkint32(3, max, true, 1, 0x7FFFFFFF, "max_steps must be >= 1")
  st = C.rg_world_set_fixed_step(p, dt, max)
  if st ~= 0 then status_error(p, st, "set_fixed_step") end
end

-- gravity and wind: a getter and a setter for a world vector.
local function world_vec2(get, set, name)
  World[name] = function(w)
    local p = open_world(w)
    local out = vec2_out() -- fresh: see vec2_out
    local st = get(p, out)
    if st ~= 0 then status_error(p, st, name) end
    return out[0].x, out[0].y
  end
  World["set_" .. name] = function(w, ...)
    local p = open_world(w)
    local st = set(p, real2(2, ...))
    if st ~= 0 then status_error(p, st, "set_" .. name) end
  end
end
world_vec2(C.rg_world_get_gravity, V.rg_world_set_gravity, "gravity")
world_vec2(C.rg_world_get_wind, V.rg_world_set_wind, "wind")

function World.integrator(w)
  local p = open_world(w)
  local st = C.rg_world_get_integrator(p, i32)
  if st ~= 0 then status_error(p, st, "integrator") end
  if i32[0] < 0 or i32[0] > 3 then raise(("integrator: unknown integrator %d"):format(i32[0])) end
  return INTEGRATORS[i32[0] + 1]
end

function World.set_integrator(w, ...)
  local p = open_world(w)
  local i = check.checkenum(2, (...), INTEGRATORS, "integrator", select("#", ...) >= 1)
  local st = C.rg_world_set_integrator(p, i)
  if st ~= 0 then status_error(p, st, "set_integrator") end
end

for _, name in ipairs{ "body_count", "spring_count", "awake_body_count", "touching_count" } do
  local count = C["rg_world_" .. name]
  World[name] = function(w) return count(open_world(w)) end
end

function World.set_sleeping(w, ...)
  local p = open_world(w)
  local st = C.rg_world_set_sleeping(p, check.checkboolean(2, (...), select("#", ...) >= 1) and 1 or 0)
  if st ~= 0 then status_error(p, st, "set_sleeping") end
end

function World.sleeping(w)
  local p = open_world(w)
  local st = C.rg_world_get_sleeping(p, i32)
  if st ~= 0 then status_error(p, st, "sleeping") end
  return i32[0] ~= 0
end

function World.set_sleep_thresholds(w, ...)
  local p = open_world(w)
  local st = C.rg_world_set_sleep_thresholds(p, real2(2, ...))
  if st ~= 0 then status_error(p, st, "set_sleep_thresholds") end
end

-- Without `position`, the world keeps the position iterations it has.
function World.set_solver_iterations(w, ...)
  local p, big = open_world(w), 0x7FFFFFFF
  local st = C.rg_world_get_solver_iterations(p, i32, i32 + 1)
  if st ~= 0 then status_error(p, st, "set_solver_iterations") end
  local velocity = check.checkint32(2, (...), select("#", ...) >= 1, -big, big, "out of range")
  local position = select(2, ...)
  position = position == nil and i32[1] or check.checkint32(3, position, true, -big, big, "out of range")
  st = C.rg_world_set_solver_iterations(p, velocity, position)
  if st ~= 0 then
    status_error(p, st, "set_solver_iterations")
  end
end

function World.solver_iterations(w)
  local p = open_world(w)
  local st = C.rg_world_get_solver_iterations(p, i32, i32 + 1)
  if st ~= 0 then status_error(p, st, "solver_iterations") end
  return i32[0], i32[1]
end

function World.set_contact_tuning(w, ...)
  local p = open_world(w)
  local st = C.rg_world_set_contact_tuning(p, real4(2, ...))
  if st ~= 0 then
    status_error(p, st, "set_contact_tuning")
  end
end

function World.set_continuous(w, ...)
  local p = open_world(w)
  local st = C.rg_world_set_continuous(p, check.checkboolean(2, (...), select("#", ...) >= 1) and 1 or 0)
  if st ~= 0 then status_error(p, st, "set_continuous") end
end

-- Live bodies in creation order.
function World.bodies(w)
  open_world(w)
  local list = {}
  for _, b in pairs(w[W_LIVE]) do list[#list + 1] = b end
  table.sort(list, function(a, b) return a[B_SERIAL] < b[B_SERIAL] end)
  return list
end

-- ---------------------------------------------------------------- world:body{...}

local BODY_OPTIONS = {
  "type", "mass", "x", "y", "vx", "vy", "gravity_scale", "drag", "surface_friction",
  "min_speed", "max_speed", "user_data", "name",
  "circle", "aabb", "restitution", "friction", "sensor", "category", "mask", "one_way",
}

-- A 64-bit user data value (a number or integer cdata) as uint64_t, bits kept.
local function user_data_bits(v)
  return ffi.cast(UINT64, ffi.cast(INT64, v))
end

-- One setting of a new body: the status so far and the option that failed, then whether
-- the option is present, its name, the call and its arguments.
local function try(st, failed, present, opt, f, ...)
  if st ~= 0 or not present then return st, failed end
  st = f(...)
  if st ~= 0 then return st, opt end
  return 0
end

function World.body(w, ...)
  local what, opts = "world:body", ...
  local p = open_world(w)
  if opts == nil then opts = {} end
  check.checktable(2, opts, true)
  option_names(opts, BODY_OPTIONS, what)
  local type_ = option_enum(opts, "type", what, TYPES) or C.RG_BODY_DYNAMIC
  local mass = option_real(opts, "mass", what) or 1
  local x, y = option_real(opts, "x", what) or 0, option_real(opts, "y", what) or 0
  local vx, vy = option_real(opts, "vx", what), option_real(opts, "vy", what)
  local has_v = vx ~= nil or vy ~= nil
  local gscale = option_real(opts, "gravity_scale", what)
  local d1, d2 = option_pair(opts, "drag", what)
  local f1, f2 = option_pair(opts, "surface_friction", what)
  local min_speed, max_speed = option_real(opts, "min_speed", what), option_real(opts, "max_speed", what)
  local user_data = option_integer(opts, "user_data", what, -2 ^ 63, 2 ^ 63,
                                   "-9223372036854775808", "9223372036854775807")
  local name = rawget(opts, "name")
  if name ~= nil and type(name) ~= "string" then option_error(what, "name", "a string", name) end
  local circle = option_real(opts, "circle", what)
  local a1, a2 = option_pair(opts, "aabb", what)
  local restitution, friction = option_real(opts, "restitution", what), option_real(opts, "friction", what)
  local sensor = check.option_boolean(opts, "sensor", what)
  local category = option_integer(opts, "category", what, 0, 0xFFFFFFFF)
  local mask = option_integer(opts, "mask", what, 0, 0xFFFFFFFF)
  local o1, o2 = option_pair(opts, "one_way", what)
  if circle and a1 then raise(what .. ": options 'circle' and 'aabb' exclude each other") end

  local st = V.rg_body_create(p, type_, mass, x, y, u64)
  if st ~= 0 then status_error(p, st, what) end
  local h, failed = u64[0], nil
  st, failed = try(st, failed, has_v, "vx/vy", V.rg_body_set_velocity, p, h, vx or 0, vy or 0)
  st, failed = try(st, failed, gscale, "gravity_scale", C.rg_body_set_gravity_scale, p, h, gscale)
  st, failed = try(st, failed, d1, "drag", C.rg_body_set_drag, p, h, d1, d2)
  st, failed = try(st, failed, f1, "surface_friction", C.rg_body_set_surface_friction, p, h, f1, f2)
  st, failed = try(st, failed, min_speed or max_speed, "min_speed/max_speed",
                   C.rg_body_set_speed_limits, p, h, min_speed or 0, max_speed or 0)
  st, failed = try(st, failed, user_data, "user_data", C.rg_body_set_user_data, p, h,
                   user_data and user_data_bits(user_data))
  st, failed = try(st, failed, circle, "circle", C.rg_body_set_circle, p, h, circle)
  st, failed = try(st, failed, a1, "aabb", C.rg_body_set_aabb, p, h, a1, a2)
  st, failed = try(st, failed, restitution, "restitution", C.rg_body_set_restitution, p, h, restitution)
  st, failed = try(st, failed, friction, "friction", C.rg_body_set_friction, p, h, friction)
  st, failed = try(st, failed, sensor ~= nil, "sensor", C.rg_body_set_sensor, p, h, sensor and 1 or 0)
  st, failed = try(st, failed, category or mask, "category/mask", C.rg_body_set_filter, p, h,
                   category or 1, mask or 0xFFFFFFFF)
  st, failed = try(st, failed, o1, "one_way", V.rg_body_set_one_way, p, h, o1, o2)
  if st ~= 0 then
    local why = check.reason(p, st)   -- before the destroy replaces it
    C.rg_body_destroy(p, h)
    raise(("%s: option '%s': %s"):format(what, failed, why))
  end
  local b, key = new_body(w, h, type_, w[W_SERIAL], name), hkey(h)
  w[W_SERIAL] = w[W_SERIAL] + 1
  w[W_LIVE][key] = b
  -- A value of a body destroyed with this handle exists only when a restore took the world
  -- back to before that body was made: it stays destroyed for good (see objects above).
  local old = w[W_DEAD][key]
  if old then
    rawset(old, B_RETIRED, true)   -- bodies have no fields to set from outside
    w[W_DEAD][key] = nil
  end
  return b
end

-- ---------------------------------------------------------------- body methods

function Body.destroy(b)
  check_body(b)
  local p, h = b[B_BOX].w, b[B_H]
  if p == nil or b[B_RETIRED] or C.rg_body_destroy(p, h) ~= 0 then return false end
  local world, key = b[B_WORLD], hkey(h)
  world[W_LIVE][key] = nil
  world[W_DEAD][key] = b
  return true
end

function Body.is_valid(b)
  local p = check_body(b)[B_BOX].w
  return p ~= nil and not b[B_RETIRED] and C.rg_body_is_valid(p, b[B_H]) ~= 0
end

function Body.name(b) return check_body(b)[B_NAME] end
function Body.world(b) return check_body(b)[B_WORLD] end
function Body.id(b) return ffi.cast(INT64, check_body(b)[B_H]) end
function body_mt.__close(b) Body.destroy(b) end

function body_mt.__tostring(b)
  check_body(b)
  local t = b[B_TYPE]
  local state = not Body.is_valid(b) and "destroyed" or TYPES[t + 1] or "?"
  if b[B_NAME] then return ('rigid.body #%d "%s" (%s)'):format(b[B_SERIAL], b[B_NAME], state) end
  return ("rigid.body #%d (%s)"):format(b[B_SERIAL], state)
end

-- One value per body, so this only matters for a value made after the first was collected.
-- A retired value is only itself: its handle names a body made after it.
function body_mt.__eq(a, b)
  return getmetatable(a) == BODY and getmetatable(b) == BODY and a[B_H] == b[B_H] and
         rawequal(a[B_BOX], b[B_BOX]) and not a[B_RETIRED] and not b[B_RETIRED]
end

function body_mt.__newindex(b)
  raise("attempt to index a rigid.body value (bodies have no fields to set)")
end

-- One function per shape of call, as in lua/lbody.c: the method's name (for errors: the
-- library says which argument broke which rule) and the library call.
local function get_vec2(name, get)
  Body[name] = function(b)
    local p, h = body_wh(b)
    local out = vec2_out()
    local st = get(p, h, out)
    if st ~= 0 then status_error(p, st, name) end
    return out[0].x, out[0].y
  end
end

local function set_vec2(name, set)
  Body[name] = function(b, ...)
    local p, h = body_wh(b)
    local st = set(p, h, real2(2, ...))
    if st ~= 0 then status_error(p, st, name) end
  end
end

local function get_real(name, get)
  Body[name] = function(b)
    local p, h = body_wh(b)
    local st = get(p, h, real)
    if st ~= 0 then status_error(p, st, name) end
    return real[0]
  end
end

local function get_real2(name, get)
  Body[name] = function(b)
    local p, h = body_wh(b)
    local st = get(p, h, real, real + 1)
    if st ~= 0 then status_error(p, st, name) end
    return real[0], real[1]
  end
end

local function set_real(name, set)
  Body[name] = function(b, ...)
    local p, h = body_wh(b)
    local st = set(p, h, real1(2, ...))
    if st ~= 0 then status_error(p, st, name) end
  end
end

-- Two numbers; when opt, an omitted second one is 0.
local function set_real2(name, set, opt)
  Body[name] = function(b, ...)
    local p, h = body_wh(b)
    local first, second
    if opt then first, second = real1(2, ...), optreal(3, select(2, ...), 0)
    else first, second = real2(2, ...) end
    local st = set(p, h, first, second)
    if st ~= 0 then status_error(p, st, name) end
  end
end

local function get_flag(name, get)
  Body[name] = function(b)
    local p, h = body_wh(b)
    local st = get(p, h, i32)
    if st ~= 0 then status_error(p, st, name) end
    return i32[0] ~= 0
  end
end

get_vec2("position", C.rg_body_get_position)
get_vec2("velocity", C.rg_body_get_velocity)
-- Where the library's by-value getters compile (lib.R), position and velocity use them: no
-- out-struct to allocate.  NaN means the call failed: the out-pointer getter says why (not
-- in a tail call, which would drop this public frame the error's position is found by).
for name, by_value in pairs{ position = lib.R.rg_body_position, velocity = lib.R.rg_body_velocity } do
  local slow = Body[name]
  Body[name] = function(b)
    local p, h = body_wh(b)
    local x, y = by_value(p, h)
    if x ~= x then x, y = slow(b) end
    return x, y
  end
end
get_vec2("interpolated_position", C.rg_body_get_interpolated_position)
get_vec2("acceleration", C.rg_body_get_acceleration)
get_vec2("one_way", C.rg_body_get_one_way)
set_vec2("set_position", V.rg_body_set_position)
set_vec2("set_velocity", V.rg_body_set_velocity)
set_vec2("apply_force", V.rg_body_apply_force)
set_vec2("apply_impulse", V.rg_body_apply_impulse)
set_vec2("set_one_way", V.rg_body_set_one_way)
get_real("mass", C.rg_body_get_mass)
get_real("restitution", C.rg_body_get_restitution)
get_real("friction", C.rg_body_get_friction)
set_real("set_mass", C.rg_body_set_mass)
set_real("set_gravity_scale", C.rg_body_set_gravity_scale)
get_real("gravity_scale", C.rg_body_get_gravity_scale)
get_real2("drag", C.rg_body_get_drag)
get_real2("speed_limits", C.rg_body_get_speed_limits)
set_real("set_restitution", C.rg_body_set_restitution)
set_real("set_friction", C.rg_body_set_friction)
set_real("set_circle", C.rg_body_set_circle)
set_real2("set_aabb", C.rg_body_set_aabb, false)
set_real2("set_drag", C.rg_body_set_drag, true)
set_real2("set_surface_friction", C.rg_body_set_surface_friction, false)
set_real2("set_speed_limits", C.rg_body_set_speed_limits, true)
get_flag("grounded", C.rg_body_is_grounded)
get_flag("is_sensor", C.rg_body_is_sensor)
get_flag("is_awake", C.rg_body_is_awake)

function Body.type(b)
  local p, h = body_wh(b)
  local st = C.rg_body_get_type(p, h, i32)
  if st ~= 0 then status_error(p, st, "type") end
  return TYPES[i32[0] + 1] or TYPES[1]
end

function Body.user_data(b)
  local p, h = body_wh(b)
  local st = C.rg_body_get_user_data(p, h, u64)
  if st ~= 0 then status_error(p, st, "user_data") end
  return int64(u64[0])
end

function Body.set_user_data(b, ...)
  local p, h = body_wh(b)
  local u = check.checkinteger(2, (...), select("#", ...) >= 1)
  local st = C.rg_body_set_user_data(p, h, user_data_bits(u))
  if st ~= 0 then status_error(p, st, "set_user_data") end
end

function Body.clear_shape(b)
  local p, h = body_wh(b)
  local st = C.rg_body_clear_shape(p, h)
  if st ~= 0 then status_error(p, st, "clear_shape") end
end

-- "circle", r | "aabb", half_width, half_height | "none"
function Body.shape(b)
  local p, h = body_wh(b)
  local st = C.rg_body_get_shape(p, h, i32, vec)
  if st ~= 0 then status_error(p, st, "shape") end
  if i32[0] == C.RG_SHAPE_CIRCLE then return "circle", vec[0].x end
  if i32[0] == C.RG_SHAPE_AABB then return "aabb", vec[0].x, vec[0].y end
  return "none"
end

function Body.set_sensor(b, ...)
  local p, h = body_wh(b)
  local s = check.checkboolean(2, (...), select("#", ...) >= 1)
  local st = C.rg_body_set_sensor(p, h, s and 1 or 0)
  if st ~= 0 then status_error(p, st, "set_sensor") end
end

function Body.set_filter(b, category, mask)
  local p, h = body_wh(b)
  local st = C.rg_body_set_filter(p, h, check.checkmask(2, category), check.checkmask(3, mask))
  if st ~= 0 then status_error(p, st, "set_filter") end
end

function Body.filter(b)
  local p, h = body_wh(b)
  local st = C.rg_body_get_filter(p, h, u32, u32 + 1)
  if st ~= 0 then status_error(p, st, "filter") end
  return u32[0], u32[1]
end

function Body.wake(b)
  local p, h = body_wh(b)
  local st = C.rg_body_wake(p, h)
  if st ~= 0 then status_error(p, st, "wake") end
end

-- ---------------------------------------------------------------- springs

local SPRING_OPTIONS = { "a", "b", "anchor", "rest_length", "stiffness", "damping" }

local function option_body(t, key, what, w)
  local b = rawget(t, key)
  if b == nil then return nil end
  if getmetatable(b) ~= BODY then option_error(what, key, "a body", b) end
  if not rawequal(b[B_BOX], w[W_BOX]) then
    raise(("%s: option '%s' is a body of another world"):format(what, key))
  end
  body_handle(b)
  return b
end

function World.spring(w, ...)
  local what, opts = "world:spring", ...
  local p = open_world(w)
  check.checktable(2, opts, select("#", ...) >= 1)
  option_names(opts, SPRING_OPTIONS, what)
  local a, b = option_body(opts, "a", what, w), option_body(opts, "b", what, w)
  if a == nil then raise(what .. ": option 'a' (a body) is required") end
  local ax, ay = option_pair(opts, "anchor", what)
  if ax == nil and b == nil then
    raise(what .. ": option 'anchor' {x, y} is required when there is no body 'b'")
  end
  local rest = option_real(opts, "rest_length", what) or 0
  local k = option_real(opts, "stiffness", what)
  if k == nil then raise(what .. ": option 'stiffness' is required") end
  local damping = option_real(opts, "damping", what) or 0
  local st = V.rg_spring_create(p, a[B_H], b and b[B_H] or 0, ax or 0, ay or 0, rest, k, damping, u64)
  if st ~= 0 then status_error(p, st, what) end
  local s, key = setmetatable({ w[W_BOX], u64[0], w, false }, spring_mt), hkey(u64[0])
  -- The value that had this handle before is retired (see objects above).
  local old = w[W_SPRINGS][key]
  if old then old[S_RETIRED] = true end
  w[W_SPRINGS][key] = s
  return s
end

local function spring_live(s)
  if getmetatable(s) ~= SPRING then typeerror(1, SPRING, s) end
  local p = s[1].w
  return p ~= nil and not s[S_RETIRED] and C.rg_spring_is_valid(p, s[2]) ~= 0
end

function Spring.destroy(s)
  if not spring_live(s) then return false end
  return C.rg_spring_destroy(s[1].w, s[2]) == 0
end

function Spring.is_valid(s) return spring_live(s) end
spring_mt.__close = Spring.destroy
function spring_mt.__tostring(s) return "rigid.spring (" .. (spring_live(s) and "live" or "destroyed") .. ")" end

-- ---------------------------------------------------------------- events, queries, contacts

do
  local core = { World = World, Body = Body, open_world = open_world, body_wh = body_wh,
                 body_handle = body_handle, push_body = push_body, new_body = new_body,
                 hkey = hkey, W_LIVE = W_LIVE, W_DEAD = W_DEAD, W_SERIAL = W_SERIAL,
                 B_BOX = B_BOX, B_H = B_H, B_WORLD = B_WORLD, B_SERIAL = B_SERIAL,
                 B_TYPE = B_TYPE, B_NAME = B_NAME }
  require("rigid_jit.contact")(core, require("rigid_jit.query")(core))
  require("rigid_jit.snapshot")(core)
end

-- ---------------------------------------------------------------- module

-- A method is known by its name (check.argerror names it so where a tail call hid it).
PUBLIC[new_world] = true
for _, t in ipairs{ world_mt, body_mt, spring_mt } do
  for _, f in pairs(t) do
    if type(f) == "function" then PUBLIC[f] = true end
  end
end
for _, t in ipairs{ World, Body, Spring } do
  for name, f in pairs(t) do
    if type(f) == "function" then PUBLIC[f] = name end
  end
end

local v = C.rg_version()
return {
  world = new_world,
  version = ("%d.%d.%d"):format(v / 10000, v / 100 % 100, v % 100),
  real_size = lib.real_size,
  collision = true,
}
