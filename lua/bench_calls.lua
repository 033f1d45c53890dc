-- bench_calls.lua: what one Lua call into rigid costs, in ns, the loop's own cost taken out.
--   LUA_CPATH="build/?.so" lua5.4 lua/bench_calls.lua       stock Lua + the module
--   build/rigid lua/bench_calls.lua --budget 0               the sandboxed host, no budget hooks
--   build/rigid lua/bench_calls.lua --budget 100000000000    the host with its hooks running
--   LUA_PATH="lua/?.lua;;" RIGID_LIBRARY=build/librigid.so luajit lua/bench_calls.lua
--                                                            LuaJIT + lua/rigid_jit.lua
-- Medians of 7 runs of N calls; CPU time from os.clock.  Timings on a shared machine are
-- noisy: compare figures from one run, not across runs.
local rigid = require(jit and "rigid_jit" or "rigid")
local N = tonumber((...)) or 2000000
local RUNS = 7

local world = rigid.world{ gravity = {0, -9.81} }
local body = world:body{ x = 1, y = 2 }
for i = 1, 999 do world:body{ x = i } end     -- a world with some bodies in it

local function median(t)
  table.sort(t)
  return t[math.floor((#t + 1) / 2)]
end

local function time(f)
  local runs = {}
  for r = 1, RUNS do
    local t0 = os.clock()
    f(N)
    runs[r] = os.clock() - t0
  end
  return median(runs)
end

local empty = time(function(n) local b = body for _ = 1, n do local _ = b end end)

local cases = {
  { "body:apply_force(fx, fy)", function(n) local b = body for _ = 1, n do b:apply_force(1, 0) end end },
  { "body:position()", function(n) local b = body for _ = 1, n do local _, _ = b:position() end end },
  { "body:velocity()", function(n) local b = body for _ = 1, n do local _, _ = b:velocity() end end },
  { "body:set_velocity(vx, vy)", function(n) local b = body for _ = 1, n do b:set_velocity(1, 0) end end },
  { "apply_force, method cached", function(n)
      local b, f = body, body.apply_force
      for _ = 1, n do f(b, 1, 0) end
    end },
  { "body:is_valid()", function(n) local b = body for _ = 1, n do local _ = b:is_valid() end end },
}

print(string.format("rigid %s (rg_real of %d bytes), %s, %d calls x %d runs, loop overhead %.1f ns",
  rigid.version, rigid.real_size, jit and jit.version or io and "stock Lua" or "sandboxed host",
  N, RUNS, empty / N * 1e9))
for _, c in ipairs(cases) do
  local t = time(c[2])
  print(string.format("  %-28s %7.1f ns per call", c[1], (t - empty) / N * 1e9))
end
