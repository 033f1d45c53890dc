-- bench_sandbox.lua: what the work the sandbox charges by size costs, the figures its
-- charges and its time limit are set from (lua/lcount.c, lua/lsandbox.c, and the snapshots'
-- in lua/lsnapshot.c).
--   build/rigid lua/bench_sandbox.lua --budget 0       (make bench-lua)
-- Each figure the best of 5 runs; CPU time from os.clock.
local RUNS = 5
local function best(f)
  local b = math.huge
  for _ = 1, RUNS do
    local t0 = os.clock()
    f()
    b = math.min(b, os.clock() - t0)
  end
  return b
end
local function line(what, seconds, per, unit)
  print(("  %-44s %9.1f ns %s"):format(what, seconds / per * 1e9, unit))
end

print("sandbox work, best of " .. RUNS .. " runs")
local N = 200000
for _, kind in ipairs({ "string", "integer", "float" }) do
  local t = {}
  for i = 1, N do t[i] = kind == "string" and "ab" or kind == "integer" and i * 7919 or i * 0.1234567 end
  line("table.concat, an element: " .. kind, best(function() table.concat(t, ",") end), N, "per element")
end
local s = ""
line('string.format("%.99f", 1e308), 408 bytes', best(function()
  for _ = 1, 1000 do s = string.format("%.99f", 1e308) end
end), 1000 * #s, "per byte written")
local fmt, data = string.rep("b", N), string.rep("\1", N)
line("string.unpack, a byte of format", best(function() string.unpack(fmt, data) end), N, "per byte")
local heap = {}
for i = 1, 300000 do heap[i] = { i } end
local bytes = collectgarbage("count") * 1024
line(("collectgarbage(), %.0f MiB heap"):format(bytes / 2 ^ 20), best(function() collectgarbage() end), bytes,
     "per heap byte")
heap = nil
collectgarbage()
line("x .. \"\" of a new float", best(function()
  for i = 1, 100000 do s = (i + 0.5) .. "" end
end), 100000, "per concatenation")
local sparse = {}
for i = 1, 1000000 do sparse[i] = true end
for i = 1, 999999 do sparse[i] = nil end
line("next(t), a million empty slots first", best(function()
  for _ = 1, 100 do next(sparse) end
end), 100, "per call")
local chain = {}
for _ = 1, 1990 do chain = setmetatable({}, { __index = chain }) end
line("a missing key through 1,990 __index tables", best(function()
  for _ = 1, 1000 do local _ = chain.missing end
end), 1000, "per lookup")
local one = {}
for i = 1, N do one[i] = i end
local function sink(...) end
local function forward(...)
  for _ = 1, 100 do sink(...) end
end
line("f(...) of 200,000 values", best(function() forward(table.unpack(one)) end), 100 * N, "per value passed")
one, sparse, chain = nil, nil, nil
collectgarbage()

-- Snapshots (lua/lsnapshot.c): a world of 10,000 circles in a pile.
local rigid = require "rigid"
local w = rigid.world{}
w:body{ type = "static", x = 0, y = -5, aabb = { 1000, 5 } }
for i = 1, 10000 do
  w:body{ x = (i % 200) * 2, y = (i // 200) * 2, vx = i % 7 - 3, circle = 0.5 + (i % 5) / 10 }
end
for _ = 1, 10 do w:step(1 / 60) end
local snap = w:save()
local clone = rigid.world{}
clone:restore(snap)
line(("world:save, %.1f MiB"):format(#snap / 2 ^ 20), best(function() w:save() end), #snap, "per byte")
line("world:restore into a clone", best(function() clone:restore(snap) end), #snap, "per byte")
line("world:save_slot", best(function() w:save_slot(0) end), #snap, "per byte")
line("world:restore_slot", best(function() w:restore_slot(0) end), #snap, "per byte")
line("world:hash", best(function() w:hash() end), #snap, "per byte")
local bad = "rgluasn1" .. string.pack("<I4", #snap) .. string.rep("\0", #snap + 8)
line("world:restore of a corrupted body list", best(function() pcall(w.restore, w, bad) end), #bad, "per byte")
bad = nil
local held = {}
local d = rigid.world{}
for i = 1, 10000 do held[i] = d:body{ x = 3 * i, circle = 1 } end
for i = 1, 10000 do held[i]:destroy() end
local empty = d:save()
line("world:restore, a destroyed body's value held", best(function() d:restore(empty) end), #held, "per value")
held, w, clone, d = nil, nil, nil, nil
collectgarbage()

local n = 0
line("a VM instruction (n = n + i)", best(function()
  for i = 1, 10000000 do n = n + i end
end), 40000000, "per instruction (4 an iteration)")
