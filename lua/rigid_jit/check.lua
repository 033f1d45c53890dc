-- rigid_jit/check.lua: the LuaJIT binding's argument and option checks, and its errors,
-- worded as lua/lcheck.c words them.
--
-- An error carries the position of the script line that called the binding (as luaL_error
-- does), and "bad argument #n to 'name'" counts as Lua 5.4 does: a method call does not
-- count self.  The binding puts every function scripts call into M.PUBLIC (a method under
-- its name), which is how the checks find that line however deep they are called.
local ffi = require "ffi"
local C = require("rigid_jit.ffi").C
local REAL = require("rigid_jit.ffi").real_size

local M = { PUBLIC = {} }
local PUBLIC = M.PUBLIC
local getinfo = debug and debug.getinfo
M.WORLD, M.BODY, M.SPRING = "rigid.world", "rigid.body", "rigid.spring"
local OURS = { [M.WORLD] = true, [M.BODY] = true, [M.SPRING] = true }

-- The level, as `error` counts from the caller of this function, of the line that called
-- the public function, and the public function's name information.
local function public_level()
  if getinfo then
    for level = 3, 30 do
      local ar = getinfo(level, "fn")
      if not ar then break end
      if PUBLIC[ar.func] then return level, ar end
    end
  end
  return 2, nil
end

function M.raise(msg)
  local level = public_level()
  error(msg, level)
end
local raise = M.raise

-- Where the script called the public function by a tail call (`return b:set_circle(r)`),
-- LuaJIT keeps no trace of the call's name or form: a method is named by its own name and
-- counted as called in the method form, the common one (Lua 5.4 reads both off the call).
function M.argerror(i, msg)
  local level, ar = public_level()
  local name, method = ar and ar.name, ar and ar.namewhat == "method"
  if ar and name == nil and type(PUBLIC[ar.func]) == "string" then
    name, method = PUBLIC[ar.func], true
  end
  name = name or "?"
  if method then
    i = i - 1
    if i == 0 then error(("calling '%s' on bad self (%s)"):format(name, msg), level) end
  end
  error(("bad argument #%d to '%s' (%s)"):format(i, name, msg), level)
end
local argerror = M.argerror

local function typename(v)        -- luaL_typeerror's name of a value
  local mt = getmetatable(v)
  return OURS[mt] and mt or type(v)
end

local function luatype(v)         -- luaL_typename: our objects are userdata in Lua 5.4
  return OURS[getmetatable(v)] and "userdata" or type(v)
end

-- present is false for an argument that was not passed ("no value").
function M.typeerror(i, expected, v, present)
  argerror(i, expected .. " expected, got " .. (present == false and "no value" or typename(v)))
end
local typeerror = M.typeerror

-- The library's reason for the failure st of the last call on world pointer p (nil: none),
-- without the C function's name, which the binding's message replaces (as lua/lcheck.c).
function M.reason(p, st)
  local why = p ~= nil and ffi.string(C.rg_world_last_error(p)) or ""
  if why == "" then return ffi.string(C.rg_status_string(st)) end
  return why:match("^rg_[%w_]*: (.*)$") or why
end

-- Raises for the failed call of status st on world pointer p: "what: " and the reason.
function M.status_error(p, st, what)
  if st == C.RG_ERR_STALE_HANDLE then raise("attempt to use a destroyed body") end
  raise(what .. ": " .. M.reason(p, st))
end

-- lua_pushfstring's %f: "%.14g", and ".0" after what would read as an integer.
local function numstr(v)
  local s = ("%.14g"):format(v)
  return s:find("^-?%d+$") and s .. ".0" or s
end

-- ---------------------------------------------------------------- arguments

local floor = math.floor
local REAL_MAX = REAL == 4 and 3.4028234663852886e38 or math.huge

local function isreal(v)
  return type(v) == "number" and v - v == 0 and v <= REAL_MAX and v >= -REAL_MAX
end

local function realerror(i, v, present)
  if type(v) ~= "number" then typeerror(i, "number", v, present)
  elseif v ~= v then argerror(i, "finite number expected, got nan")
  elseif v - v ~= 0 then argerror(i, "finite number expected, got inf")
  else argerror(i, "number out of range for rg_real (float)") end
end

-- Arguments i (and i + 1) from the first vararg(s).
function M.real1(i, ...)
  local v = ...
  if not isreal(v) then realerror(i, v, select("#", ...) >= 1) end
  return v
end

function M.real2(i, ...)
  local x, y = ...
  if not isreal(x) then realerror(i, x, select("#", ...) >= 1) end
  if not isreal(y) then realerror(i + 1, y, select("#", ...) >= 2) end
  return x, y
end

function M.real4(i, ...)
  local a, b, c, d = ...
  local n = select("#", ...)
  if not isreal(a) then realerror(i, a, n >= 1) end
  if not isreal(b) then realerror(i + 1, b, n >= 2) end
  if not isreal(c) then realerror(i + 2, c, n >= 3) end
  if not isreal(d) then realerror(i + 3, d, n >= 4) end
  return a, b, c, d
end

function M.optreal(i, v, def)
  if v == nil then return def end
  if not isreal(v) then realerror(i, v, true) end
  return v
end

local function isint(v)
  return type(v) == "number" and v == floor(v) and v >= -2 ^ 63 and v < 2 ^ 63
end

function M.isint64(v)               -- 64-bit integer cdata
  return type(v) == "cdata" and (ffi.istype("int64_t", v) or ffi.istype("uint64_t", v))
end
local isint64 = M.isint64

-- luaL_checkinteger: numeric strings convert; 64-bit integer cdata pass too.
function M.checkinteger(i, v, present)
  local n = type(v) == "string" and tonumber(v) or v
  if isint64(n) then return n end
  if type(n) ~= "number" then typeerror(i, "number", v, present) end
  if not isint(n) then argerror(i, "number has no integer representation") end
  return n
end
local checkinteger = M.checkinteger

function M.checkint32(i, v, present, lo, hi, msg)
  v = checkinteger(i, v, present)
  if not (v >= lo and v <= hi) then argerror(i, msg) end
  return v
end

function M.checkmask(i, v)
  if not (isint(v) and v >= 0 and v <= 0xFFFFFFFF) then
    argerror(i, "integer in [0, 0xFFFFFFFF] expected")
  end
  return v
end

function M.optmask(i, v)
  if v == nil then return 0xFFFFFFFF end
  return M.checkmask(i, v)
end

function M.checkboolean(i, v, present)
  if type(v) ~= "boolean" then typeerror(i, "boolean", v, present) end
  return v
end

function M.checktable(i, v, present)
  if type(v) ~= "table" or OURS[getmetatable(v)] then typeerror(i, "table", v, present) end
  return v
end

local function names_list(names) return table.concat(names, ", ") end

-- One of names (a list); returns its index from 0, as the C enum counts.
function M.checkenum(i, v, names, what, present)
  if type(v) ~= "string" then typeerror(i, "string", v, present) end
  for k = 1, #names do if names[k] == v then return k - 1 end end
  argerror(i, ("invalid %s '%s' (%s)"):format(what, v, names_list(names)))
end

-- ---------------------------------------------------------------- option tables
--
-- Each option_* returns the option's value(s), nil when it is absent, and raises when it
-- is present and wrong.

function M.option_names(t, names, what)
  local known = {}
  for _, n in ipairs(names) do known[n] = true end
  for k in next, t do
    if type(k) ~= "string" then
      raise(("%s: option names must be strings (got a %s key)"):format(what, luatype(k)))
    end
    if not known[k] then
      raise(("%s: unknown option '%s' (known: %s)"):format(what, k, names_list(names)))
    end
  end
end

function M.option_error(what, key, expected, v)
  raise(("%s: option '%s' must be %s (got %s)"):format(what, key, expected, luatype(v)))
end
local option_error = M.option_error

function M.option_real(t, key, what)
  local v = rawget(t, key)
  if v == nil then return nil end
  if type(v) ~= "number" then option_error(what, key, "a number", v) end
  if not isreal(v) then
    raise(("%s: option '%s' must be a finite number (got %s)"):format(what, key, numstr(v)))
  end
  return v
end

-- An integer in [lo, hi] (shown as los and his when given); a signed range (user data)
-- takes 64-bit integer cdata too.
function M.option_integer(t, key, what, lo, hi, los, his)
  local v = rawget(t, key)
  if v == nil or isint64(v) and lo < 0 then return v end
  if not (isint(v) and v >= lo and v <= hi) then
    if type(v) ~= "number" then option_error(what, key, "an integer", v) end
    raise(("%s: option '%s' must be an integer in [%s, %s]"):format(what, key, los or lo, his or hi))
  end
  return v
end

local PAIR = "a table {a, b} of two numbers"
-- A pair {a, b} of finite numbers: vectors, drag coefficients, box half sizes.
function M.option_pair(t, key, what)
  local v = rawget(t, key)
  if v == nil then return nil end
  if type(v) ~= "table" or OURS[getmetatable(v)] then option_error(what, key, PAIR, v) end
  local n = 0
  for k in next, v do
    n = n + 1
    if not (isint(k) and k >= 1 and k <= 2) then
      raise(("%s: option '%s' must be %s (it has key %s)"):format(what, key, PAIR, tostring(k)))
    end
  end
  if n ~= 2 then raise(("%s: option '%s' must be %s"):format(what, key, PAIR)) end
  for i = 1, 2 do
    local x = rawget(v, i)
    if type(x) ~= "number" then
      raise(("%s: option '%s' must be %s (item %d is a %s)"):format(what, key, PAIR, i, luatype(x)))
    end
    if not isreal(x) then
      raise(("%s: option '%s' must hold finite numbers (item %d is %s)"):format(what, key, i,
                                                                              numstr(x)))
    end
  end
  return rawget(v, 1), rawget(v, 2)
end

function M.option_boolean(t, key, what)
  local v = rawget(t, key)
  if v ~= nil and type(v) ~= "boolean" then option_error(what, key, "a boolean", v) end
  return v
end

function M.option_enum(t, key, what, names)
  local v = rawget(t, key)
  if v == nil then return nil end
  if type(v) ~= "string" then option_error(what, key, "a string", v) end
  for k = 1, #names do if names[k] == v then return k - 1 end end
  raise(("%s: option '%s' has no value '%s' (%s)"):format(what, key, v, names_list(names)))
end

M.INTEGRATORS = { "explicit", "semi_implicit", "verlet", "rk4" }
M.TYPES = { "static", "kinematic", "dynamic" }

return M
