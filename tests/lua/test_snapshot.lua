-- test_snapshot.lua: world:save(), world:restore(s) and world:hash(): round trips that
-- resimulate to the same bytes, the identity of body values across a restore, and bad
-- strings that raise and change nothing; and the kept states (world:save_slot(k),
-- restore_slot(k), drop_slot(k)).  Runs where tests/lua/test_rigid.lua runs: in the
-- sandboxed host, in stock lua5.4 and in LuaJIT through lua/rigid_jit.lua, one script for
-- all.  (Its few helpers repeat test_rigid.lua's: the sandbox loads no second file.)
-- Prints "N passed, N failed" and fails when anything failed.
local rigid = require(jit and "rigid_jit" or "rigid")

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

-- f(...) must raise an error whose message contains `text` (plain).
local function raises(text, f, ...)
  local ok, err = pcall(f, ...)
  if ok then error("expected an error containing '" .. text .. "', got none", 2) end
  if not tostring(err):find(text, 1, true) then
    error("expected an error containing '" .. text .. "', got: " .. tostring(err), 2)
  end
end

local DT = 1 / 60

local function steps(w, n) for _ = 1, n do w:step(DT) end end

-- Everything a game reads of a world after a step, as one string: every body's position and
-- velocity (%a: the exact bits), the events of the step (kind, bodies by name, normal,
-- depth) and the hash.
local function state(w)
  local t = {}
  for _, b in ipairs(w:bodies()) do
    local x, y = b:position()
    local vx, vy = b:velocity()
    t[#t + 1] = ("%s %a %a %a %a %s"):format(b:name() or "?", x, y, vx, vy, tostring(b:is_awake()))
  end
  for _, e in ipairs(w:events()) do
    t[#t + 1] = ("%s %s %s %a %a %a"):format(e.kind, e.a:name() or "?", e.b:name() or "?", e.nx,
                                            e.ny, e.depth)
  end
  t[#t + 1] = tostring(w:hash())
  return table.concat(t, "\n")
end

-- A scene with every feature a step has: a floor and a wall, a kinematic lift, a sensor, a
-- pile of bouncing balls (they collide, fall asleep), two springs, and a bullet that only
-- continuous collision stops at the wall.
local function scene(w, integrator)
  w:set_gravity(0, -10)
  w:set_integrator(integrator)
  w:set_sleeping(true)
  w:set_continuous(true)
  w:body{ type = "static", aabb = {10, 0.5}, y = -0.5, name = "floor" }
  w:body{ type = "static", aabb = {0.005, 2}, x = 9, y = 2, name = "wall" }
  w:body{ type = "kinematic", aabb = {1, 0.1}, x = 5, y = 1, vy = 0.25, name = "lift" }
  w:body{ type = "static", aabb = {1, 1}, x = -4, y = 1, sensor = true, name = "coin" }
  local balls = {}
  for i = 1, 6 do
    balls[i] = w:body{ circle = 0.25, x = -3 + 0.9 * i, y = 0.5 + 0.6 * i, restitution = 0.3,
                       name = "ball" .. i }
  end
  w:body{ circle = 0.05, x = -8, y = 0.3, vx = 300, gravity_scale = 0, name = "bullet" }
  w:spring{ a = balls[1], b = balls[2], rest_length = 1, stiffness = 50, damping = 1 }
  w:spring{ a = balls[6], anchor = {3, 6}, rest_length = 2, stiffness = 20 }
  return balls
end

-- ---------------------------------------------------------------- round trips

test("save at step k, run to n, restore, run to n again: the same bytes, every integrator", function()
  for _, integrator in ipairs{ "explicit", "semi_implicit", "verlet", "rk4" } do
    local w = rigid.world()
    scene(w, integrator)
    steps(w, 30)
    local s, at_save = w:save(), state(w)
    check(type(s) == "string" and #s > 0, "save returns a string")
    local first = {}
    for i = 1, 90 do w:step(DT); first[i] = state(w) end
    w:restore(s)
    eq(state(w), at_save, integrator .. ": the state at the save, events included")
    for i = 1, 90 do
      w:step(DT)
      if state(w) ~= first[i] then error(integrator .. ": step " .. (30 + i) .. " differs after the restore") end
    end
    check(first[90]:find("bullet", 1, true), "the scene ran")
  end
end)

test("a snapshot restored into a fresh world continues to the same bytes", function()
  local a = rigid.world()
  scene(a, "verlet")
  steps(a, 40)
  local s = a:save()
  local b = rigid.world()
  b:restore(s)
  eq(b:hash(), a:hash(), "the clone hashes as the original")
  eq(#b:bodies(), #a:bodies(), "bodies")
  for i, body in ipairs(b:bodies()) do
    eq(body:name(), a:bodies()[i]:name(), "names in creation order")
    eq(tostring(body), tostring(a:bodies()[i]), "tostring: serial, name and type")
  end
  eq(b:spring_count(), 2, "springs")
  for _ = 1, 60 do a:step(DT); b:step(DT) end
  eq(state(b), state(a), "after 60 more steps")
end)

test("a snapshot taken again after a restore is the same string", function()
  local w = rigid.world()
  scene(w, "semi_implicit")
  steps(w, 20)
  local s = w:save()
  steps(w, 20)
  w:body{ circle = 1, y = 5, name = "late" }
  w:restore(s)
  eq(w:save(), s, "save after restore")
end)

test("hash: equal states give equal hashes, a step changes it", function()
  local a, b = rigid.world(), rigid.world()
  scene(a, "rk4")
  scene(b, "rk4")
  if jit then check(require("ffi").istype("int64_t", a:hash()), "LuaJIT: an int64_t cdata")
  else eq(math.type(a:hash()), "integer", "Lua 5.4: an integer") end
  eq(a:hash(), b:hash(), "two worlds built by the same calls")
  a:step(DT)
  check(a:hash() ~= b:hash(), "one step apart")
  b:step(DT)
  eq(a:hash(), b:hash(), "the same step")
  eq(a:hash(), a:hash(), "hashing changes nothing")
end)

test("events: a restored world reads the events it had when saved", function()
  local w = rigid.world{ gravity = {0, -10} }
  local floor = w:body{ type = "static", aabb = {5, 0.5}, y = -0.5, name = "floor" }
  local ball = w:body{ circle = 0.25, y = 0.3, vy = -1, name = "ball" }
  local n = 0
  repeat w:step(DT); n = n + 1 until #w:events() > 0 or n > 60
  local s = w:save()
  local e = w:events()[1]
  steps(w, 5)
  w:restore(s)
  local again = w:events()
  eq(#again, 1, "one event")
  eq(again[1].kind, e.kind, "kind")
  check(rawequal(again[1].a, e.a) and rawequal(again[1].b, e.b), "the same body values")
  check(rawequal(e.a, floor) or rawequal(e.a, ball), "bodies of the scene")
end)

-- ---------------------------------------------------------------- identity

test("a body value from before the save is the same value after the restore", function()
  local w = rigid.world{ gravity = {0, -10} }
  local balls = scene(w, "semi_implicit")
  local seen = {}
  for i, b in ipairs(balls) do seen[b] = i end
  steps(w, 10)
  local s = w:save()
  local x, y = balls[3]:position()
  steps(w, 30)
  w:restore(s)
  for _, b in ipairs(w:bodies()) do
    if b:name():find("^ball") then eq(seen[b], tonumber(b:name():match("%d+")), "a table keyed by body") end
  end
  local x2, y2 = balls[3]:position()
  eq(x2, x, "x"); eq(y2, y, "y")
  for i, b in ipairs(balls) do check(rawequal(w:bodies()[4 + i], b), "world:bodies() gives the same values") end
end)

test("bodies created after the save are destroyed by the restore", function()
  local w = rigid.world()
  local keep = w:body{ circle = 1, name = "keep" }
  local s = w:save()
  local late = w:body{ circle = 1, x = 5, name = "late" }
  eq(w:body_count(), 2)
  w:restore(s)
  eq(w:body_count(), 1, "body count")
  check(not late:is_valid(), "is_valid")
  check(tostring(late):find('"late" (destroyed)', 1, true), tostring(late))
  raises("attempt to use a destroyed body", late.position, late)
  raises("attempt to use a destroyed body", late.set_velocity, late, 1, 0)
  raises("attempt to use a destroyed body", w.spring, w, { a = keep, b = late, stiffness = 1 })
  eq(late:destroy(), false, "destroy")
  eq(#w:bodies(), 1, "world:bodies()")
  check(rawequal(w:bodies()[1], keep), "the kept body")
  eq(late:name(), "late", "a destroyed body keeps its name")
end)

test("bodies destroyed after the save live again: the same value when still held", function()
  local w = rigid.world()
  local a = w:body{ circle = 1, x = 1, name = "a" }
  local b = w:body{ circle = 1, x = 2, name = "b" }
  local gone = w:body{ aabb = {1, 2}, x = 3, type = "static", name = "gone" }
  local gone_id, gone_str = gone:id(), tostring(gone)
  local s = w:save()
  check(a:destroy() and b:destroy() and gone:destroy(), "destroyed")
  gone = nil
  collectgarbage(); collectgarbage()
  w:restore(s)
  check(a:is_valid() and b:is_valid(), "held values live again")
  local x = a:position()
  eq(x, 1, "a's position")
  local list = w:bodies()
  eq(#list, 3, "three bodies")
  check(rawequal(list[1], a) and rawequal(list[2], b), "the held values, in creation order")
  local again = list[3]
  eq(again:id(), gone_id, "the collected one comes back with its handle")
  eq(again:name(), "gone", "and its name")
  eq(tostring(again), gone_str, "serial, name and type")
  local kind, hw, hh = again:shape()
  eq(kind, "aabb"); eq(hw, 1); eq(hh, 2)
  eq(again:type(), "static")
end)

test("a handle given out again after a restore is a new value; the old one stays destroyed", function()
  local w = rigid.world()
  local anchor = w:body{ circle = 1, name = "anchor" }
  local s = w:save()
  local first = w:body{ circle = 0.5, x = 2, name = "first" }
  local rope = w:spring{ a = anchor, b = first, stiffness = 1 }
  w:restore(s)
  local second = w:body{ circle = 0.5, x = 2, name = "second" }
  local rope2 = w:spring{ a = anchor, b = second, stiffness = 1 }
  eq(second:id(), first:id(), "the same creation after the rollback takes the same handle")
  check(second:is_valid() and not first:is_valid(), "only the new value is live")
  check(not rawequal(first, second) and first ~= second, "two values, not equal")
  raises("attempt to use a destroyed body", first.position, first)
  eq(first:destroy(), false, "destroying the old value")
  check(second:is_valid(), "leaves the new one")
  check(tostring(first):find("(destroyed)", 1, true), tostring(first))
  check(rope2:is_valid() and not rope:is_valid(), "springs: only the new value is live")
  eq(rope:destroy(), false, "destroying the old spring value")
  check(rope2:is_valid(), "leaves the new spring")
  eq(w:spring_count(), 1)
  w:restore(s)
  check(not second:is_valid() and not first:is_valid(), "a second restore destroys the second")
end)

test("shapes, types and names follow the restored state", function()
  local w = rigid.world()
  local b = w:body{ circle = 0.5, name = "b" }
  local s = w:save()
  b:set_aabb(1, 2)
  b:set_sensor(true)
  w:restore(s)
  local kind, r = b:shape()
  eq(kind, "circle"); eq(r, 0.5)
  eq(b:is_sensor(), false, "sensor flag")
  -- Restored into another world, the values there take the saved names and types.
  local other = rigid.world()
  local mine = other:body{ type = "static", aabb = {1, 1}, name = "mine" }
  other:restore(s)
  check(not mine:is_valid(), "the other world's own bodies are gone")
  local list = other:bodies()
  eq(#list, 1)
  eq(list[1]:name(), "b")
  check(tostring(list[1]):find('"b" (dynamic)', 1, true), tostring(list[1]))
  eq(list[1]:id(), b:id(), "the clone answers the original's handle")
end)

test("many rollbacks: identity holds, nothing grows", function()
  local w = rigid.world{ gravity = {0, -10} }
  local balls = scene(w, "semi_implicit")
  steps(w, 5)
  local s, h = w:save(), w:hash()
  local base
  for round = 1, 1000 do
    w:restore(s)
    if w:hash() ~= h then error("round " .. round .. ": the hash after the restore") end
    local shot = w:body{ circle = 0.1, x = -5, y = 4, vx = 3, name = "shot" }
    steps(w, 2)
    if not (shot:is_valid() and balls[1]:is_valid()) then error("round " .. round) end
    if round == 200 then collectgarbage(); collectgarbage(); base = collectgarbage("count") end
  end
  collectgarbage(); collectgarbage()
  -- A value kept per round would be 800 values of 40 bytes or more by now, 31 KiB; half
  -- of that leaves room for what LuaJIT's compiler allocates once (it once grew 8.5 KiB
  -- between rounds 100 and 400 of a shorter run with nothing kept).
  check(collectgarbage("count") - base < 16, ("Lua memory grew by %.1f KiB"):format(collectgarbage("count") - base))
  w:restore(s)
  eq(#w:bodies(), 11, "the scene's bodies")
end)

-- ---------------------------------------------------------------- bad strings

-- Byte helpers for forging: a little-endian u32, and the FNV-1a of the format as 8 bytes.
local function u32(s, off)
  local a, b, c, d = s:byte(off + 1, off + 4)
  return a + b * 256 + c * 65536 + d * 16777216
end
local function le32(v)
  return string.char(v % 256, math.floor(v / 256) % 256, math.floor(v / 65536) % 256,
                     math.floor(v / 16777216) % 256)
end
local fnv8 = jit and load([[
  local bit = require "bit"
  return function(s)
    local h = 0xcbf29ce484222325ULL
    for i = 1, #s do h = bit.bxor(h, s:byte(i)) * 0x100000001b3ULL end
    local t = {}
    for i = 1, 8 do t[i] = tonumber(bit.band(h, 0xFF)); h = bit.rshift(h, 8) end
    return string.char(unpack(t))
  end]])() or load([[
  return function(s)
    local h = 0xcbf29ce484222325
    for i = 1, #s do h = (h ~ s:byte(i)) * 0x100000001b3 end
    return string.pack("<i8", h)
  end]])()

-- s with its body list replaced by count entries made of the byte strings given.
local function forge(s, count, entries)
  local n = u32(s, 8)
  local list = s:sub(13, 20) .. le32(count) .. table.concat(entries)
  local head = "rgluasn1" .. le32(#list) .. list
  return head .. fnv8(head) .. s:sub(12 + n + 9)
end

-- The entries of s's body list, as byte strings.
local function entries_of(s)
  local out, at = {}, 24
  for _ = 1, u32(s, 20) do
    local len = u32(s, at + 16)
    len = len == 0xFFFFFFFF and 0 or len
    out[#out + 1] = s:sub(at + 1, at + 20 + len)
    at = at + 20 + len
  end
  return out
end

local function small_world()
  local w = rigid.world{ gravity = {0, -10} }
  w:body{ type = "static", aabb = {4, 0.5}, y = -0.5, name = "floor" }
  local a = w:body{ circle = 0.25, y = 1, name = "a" }
  w:body{ circle = 0.25, x = 1, y = 2 }
  steps(w, 20)
  return w, a
end

-- Restoring bad must raise `text` and leave the world as it was.
local function refused(w, text, bad, what)
  local h, list, late = w:hash(), w:bodies(), w:bodies()[#w:bodies()]
  local ok, err = pcall(function() w:restore(bad) end)
  if ok then error(what .. ": accepted", 2) end
  if not tostring(err):find(text, 1, true) then error(what .. ": " .. tostring(err), 2) end
  if w:hash() ~= h then error(what .. ": the world changed", 2) end
  local now = w:bodies()
  if #now ~= #list or not rawequal(now[#now], late) or not late:is_valid() then
    error(what .. ": the bodies changed", 2)
  end
end

test("restore: every truncation raises and changes nothing", function()
  local w = small_world()
  local s = w:save()
  w:body{ circle = 0.1, x = -2, name = "after" }
  steps(w, 3)
  for len = 0, #s - 1 do refused(w, "restore: ", s:sub(1, len), "length " .. len) end
  refused(w, "restore: ", s .. "x", "one byte more")
end)

test("restore: every byte flipped raises and changes nothing", function()
  local w = small_world()
  local s = w:save()
  steps(w, 3)
  for i = 1, #s do
    local flipped = s:sub(1, i - 1) .. string.char((s:byte(i) + 1 + i % 254) % 256) .. s:sub(i + 1)
    refused(w, "restore: ", flipped, "byte " .. i)
  end
  refused(w, "checksum mismatch (the snapshot's body list is corrupted)",
          s:sub(1, 30) .. string.char((s:byte(31) + 1) % 256) .. s:sub(32), "a handle's byte")
  refused(w, "restore: checksum mismatch", s:sub(1, #s - 9) .. string.char((s:byte(#s - 8) + 1) % 256) ..
          s:sub(#s - 7), "a byte of the library's snapshot")
end)

test("restore: not a snapshot, garbage, wrong types", function()
  local w = small_world()
  refused(w, "restore: not a snapshot of world:save (0 bytes)", "", "empty")
  refused(w, "restore: not a snapshot of world:save (11 bytes)", "hello world", "text")
  local seed, junk = 12345, {}
  for i = 1, 3000 do seed = (seed * 1103515245 + 12345) % 2147483648; junk[i] = string.char(seed % 256) end
  junk = table.concat(junk)
  refused(w, "restore: not a snapshot", junk, "random bytes")
  refused(w, "restore: ", "rgluasn1" .. junk, "random bytes after the magic")
  local other = rigid.world()
  refused(w, "restore: ", "rgluasn1" .. other:save():sub(9, 24) .. junk, "a body list before garbage")
  for _, v in ipairs{ 42, true, {}, w } do
    refused(w, "bad argument #1 to 'restore' (string expected, got ", v, "a " .. type(v))
  end
  raises("bad argument #1 to 'restore' (string expected, got no value)", function() w:restore() end)
  raises("bad argument #1 to 'restore' (string expected, got number)", function() w:restore(7) end)
end)

test("restore: a forged body list with a good checksum raises and changes nothing", function()
  local w = small_world()
  local s = w:save()
  local e = entries_of(s)
  eq(#e, 3, "three entries")
  eq(w:restore(forge(s, 3, e)), nil, "the unforged list, rebuilt, is accepted")
  steps(w, 2)
  refused(w, "body list does not match its world (2 bodies listed, 3 in the world)",
          forge(s, 2, { e[1], e[2] }), "a body left out")
  refused(w, "body list is malformed (body 3 twice)", forge(s, 3, { e[1], e[2], e[1] }), "twice")
  refused(w, "body list is malformed", forge(s, 4, e), "a count too large")
  refused(w, "body list is malformed", forge(s, 3, { e[1], e[2], e[3]:sub(1, 19) }), "a cut entry")
  local zero = ("\0"):rep(8) .. e[3]:sub(9)
  refused(w, "body list is malformed (entry 3)", forge(s, 3, { e[1], e[2], zero }), "handle 0")
end)

test("save, restore and hash of a closed world raise", function()
  local w = rigid.world()
  local s = w:save()
  w:close()
  raises("attempt to use a closed world", w.save, w)
  raises("attempt to use a closed world", w.restore, w, s)
  raises("attempt to use a closed world", w.hash, w)
  raises("rigid.world expected, got nil", w.hash, nil)
end)

-- ---------------------------------------------------------------- kept states

test("a kept state brings the world back as its snapshot would, every integrator", function()
  for _, integrator in ipairs{ "explicit", "semi_implicit", "verlet", "rk4" } do
    local w = rigid.world()
    scene(w, integrator)
    steps(w, 30)
    w:save_slot(7)
    local s, at_keep = w:save(), state(w)
    local first = {}
    for i = 1, 60 do w:step(DT); first[i] = state(w) end
    w:body{ circle = 1, y = 5, name = "late" }
    w:restore_slot(7)
    eq(w:save(), s, integrator .. ": the snapshot string of the moment kept")
    eq(state(w), at_keep, integrator .. ": the state, events included")
    for i = 1, 60 do
      w:step(DT)
      if state(w) ~= first[i] then error(integrator .. ": step " .. (30 + i) .. " differs after the restore") end
    end
  end
end)

test("a kept state keeps body values as a restore does", function()
  local w = rigid.world()
  local a = w:body{ circle = 1, x = 1, name = "a" }
  local gone = w:body{ circle = 1, x = 2, name = "gone" }
  w:save_slot(0)
  local late = w:body{ circle = 1, x = 5, name = "late" }
  check(gone:destroy(), "destroyed")
  w:restore_slot(0)
  local list = w:bodies()
  eq(#list, 2, "two bodies")
  check(rawequal(list[1], a) and rawequal(list[2], gone), "the same values, in creation order")
  check(gone:is_valid() and not late:is_valid(), "the destroyed one lives, the late one is gone")
  eq(gone:name(), "gone", "its name")
  raises("attempt to use a destroyed body", late.position, late)
end)

test("slots are independent; a dropped one is empty", function()
  local w = rigid.world()
  scene(w, "semi_implicit")
  local h = {}
  for _, k in ipairs{ 0, 1, 63 } do
    steps(w, 9)
    w:save_slot(k)
    h[k] = w:hash()
  end
  check(h[0] ~= h[1] and h[1] ~= h[63], "three moments")
  for _, k in ipairs{ 1, 63, 0, 1 } do
    w:restore_slot(k)
    eq(w:hash(), h[k], "slot " .. k)
    steps(w, 4)
  end
  w:drop_slot(1)
  raises("restore_slot: slot 1 is empty", w.restore_slot, w, 1)
  w:drop_slot(1)   -- an empty slot: no error
  w:restore_slot(63)
  eq(w:hash(), h[63], "the others stay")
end)

test("bad slots raise and change nothing", function()
  local w = rigid.world()
  scene(w, "semi_implicit")
  steps(w, 5)
  local before = state(w)
  raises("slot must be in [0, 64)", w.save_slot, w, -1)
  raises("slot must be in [0, 64)", w.save_slot, w, 64)
  raises("slot must be in [0, 64)", w.restore_slot, w, 64)
  raises("slot must be in [0, 64)", w.drop_slot, w, -1)
  raises("number expected", w.save_slot, w, "one")
  raises("restore_slot: slot 5 is empty", w.restore_slot, w, 5)
  eq(state(w), before, "the world")
  w:close()
  raises("attempt to use a closed world", w.save_slot, w, 0)
  raises("attempt to use a closed world", w.restore_slot, w, 0)
end)

print(passed .. " passed, " .. failed .. " failed")
if failed > 0 then error(failed .. " Lua test(s) failed", 0) end
