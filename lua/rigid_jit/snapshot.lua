-- rigid_jit/snapshot.lua: world:save(), world:restore(s) and world:hash() in the LuaJIT
-- binding, as lua/lsnapshot.c has them and in its format (described there): the library's
-- snapshot with the binding's list of the live bodies (handle, serial, name).  A restore
-- puts every body value where the restored world says it is, and changes nothing unless
-- all of it succeeds.  world:hash() returns the 64 bits as an int64_t cdata (the bits Lua
-- 5.4 shows as an integer): == compares two hashes, tostring prints them.  The kept states
-- (world:save_slot(k), restore_slot(k), drop_slot(k)) pair the library's with the body
-- list of the moment, as lsnapshot.c does.  rigid_jit.lua
-- calls the function this returns with its core (it returns nothing).
local ffi = require "ffi"
local bit = require "bit"
local lib = require "rigid_jit.ffi"
local check = require "rigid_jit.check"

local C = lib.C
local raise, typeerror, status_error = check.raise, check.typeerror, check.status_error

local MAGIC, HEAD, ENTRY, NONAME = "rgluasn1", 12, 20, 0xFFFFFFFF
local U64, I64 = ffi.typeof("uint64_t"), ffi.typeof("int64_t")
local BYTES = ffi.typeof("uint8_t[?]")
local size = ffi.new("size_t[1]")
local hash = ffi.new("uint64_t[1]")
local i32 = ffi.new("int32_t[1]")
local char, byte, sub, concat = string.char, string.byte, string.sub, table.concat

-- n little-endian bytes of v (a number or a 64-bit integer cdata).
local function le(v, n)
  local t = {}
  v = ffi.cast(U64, ffi.cast(I64, v))
  for i = 1, n do
    t[i] = tonumber(bit.band(v, 0xFF))
    v = bit.rshift(v, 8)
  end
  return char(unpack(t))
end

-- The n little-endian bytes of s from offset off (0-based) as a uint64_t.
local function get(s, off, n)
  local v = ffi.new(U64, 0)
  for i = n, 1, -1 do v = bit.bor(bit.lshift(v, 8), byte(s, off + i)) end
  return v
end

local function fnv(s)
  local h = 0xcbf29ce484222325ULL
  for i = 1, #s do h = bit.bxor(h, byte(s, i)) * 0x100000001b3ULL end
  return h
end

-- The body list of snapshot string s, checked as lua/lsnapshot.c checks it:
-- { next_serial, entries = { { h, serial, name }... } } and where the library's part starts.
local function read(s)
  local len = #s
  if len < HEAD or sub(s, 1, 8) ~= MAGIC then
    raise(("restore: not a snapshot of world:save (%d bytes)"):format(len))
  end
  local n = tonumber(get(s, 8, 4))
  if n > len - HEAD or len - HEAD - n < 8 then
    raise(("restore: truncated (%d bytes; its body list alone needs %d)"):format(len, HEAD + n + 8))
  end
  if get(s, HEAD + n, 8) ~= fnv(sub(s, 1, HEAD + n)) then
    raise("restore: checksum mismatch (the snapshot's body list is corrupted)")
  end
  local malformed = "restore: the snapshot's body list is malformed"
  local at, stop = HEAD, HEAD + n
  if n < 12 then raise(malformed) end
  local next_serial = ffi.cast(I64, get(s, at, 8))
  local count = tonumber(get(s, at + 8, 4))
  at = at + 12
  if next_serial < 1 or count > 0x7FFFFFFF or count > math.floor((stop - at) / ENTRY) then
    raise(malformed)
  end
  local entries, i = {}, 1
  while i <= count do
    if stop - at < ENTRY then break end
    local h, serial = get(s, at, 8), ffi.cast(I64, get(s, at + 8, 8))
    local raw = tonumber(get(s, at + 16, 4))
    if raw ~= NONAME and raw > stop - at - ENTRY then break end
    local name = raw ~= NONAME and sub(s, at + ENTRY + 1, at + ENTRY + raw) or nil
    at = at + ENTRY + (name and raw or 0)
    if h == 0 or serial < 1 or serial >= next_serial then break end
    entries[i] = { h, tonumber(serial), name }
    i = i + 1
  end
  if i <= count or at ~= stop then raise(("%s (entry %d)"):format(malformed, i)) end
  return { next_serial = tonumber(next_serial), entries = entries }, HEAD + n + 8
end

return function(core)
  local World, open_world, new_body, hkey = core.World, core.open_world, core.new_body, core.hkey
  local W_LIVE, W_DEAD, W_SERIAL = core.W_LIVE, core.W_DEAD, core.W_SERIAL
  local B_H, B_SERIAL, B_TYPE, B_NAME = core.B_H, core.B_SERIAL, core.B_TYPE, core.B_NAME

  -- The library's snapshot of world pointer p, as a string.
  local function library_snapshot(p, what)
    local st = C.rg_world_save(p, nil, 0, size)
    if st ~= 0 then status_error(p, st, what) end
    local n = size[0]
    local buf = BYTES(n)
    st = C.rg_world_save(p, buf, n, size)
    if st ~= 0 then status_error(p, st, what) end
    return ffi.string(buf, n)
  end

  local function by_creation(a, b)
    if a[B_SERIAL] ~= b[B_SERIAL] then return a[B_SERIAL] < b[B_SERIAL] end
    return ffi.cast(I64, a[B_H]) < ffi.cast(I64, b[B_H])
  end

  -- The live bodies of w in creation order, as read() gives a list: { next_serial, entries }.
  local function list_of(w)
    local bodies = {}
    for _, b in pairs(w[W_LIVE]) do bodies[#bodies + 1] = b end
    table.sort(bodies, by_creation)
    local entries = {}
    for i, b in ipairs(bodies) do entries[i] = { b[B_H], b[B_SERIAL], b[B_NAME] } end
    return { next_serial = w[W_SERIAL], entries = entries }
  end

  function World.save(w)
    local p = open_world(w)
    local l = list_of(w)
    local list = { le(l.next_serial, 8), le(#l.entries, 4) }
    for i, e in ipairs(l.entries) do
      local name = e[3]
      list[i + 2] = le(e[1], 8) .. le(e[2], 8) .. le(name and #name or NONAME, 4) .. (name or "")
    end
    list = concat(list)
    local head = MAGIC .. le(#list, 4) .. list
    return head .. le(fnv(head), 8) .. library_snapshot(p, "save")
  end

  -- Everything the swap to list needs, made before anything changes: the new live and dead
  -- tables and the list's body values in its order.
  local function prepare(w, list)
    local live, dead = w[W_LIVE], w[W_DEAD]
    local new_live, new_dead = {}, setmetatable({}, getmetatable(dead))
    local values = {}
    for i, e in ipairs(list.entries) do
      local key = hkey(e[1])
      if new_live[key] then
        raise(("restore: the snapshot's body list is malformed (body %d twice)"):format(i))
      end
      local b = live[key] or dead[key] or new_body(w, e[1], -1, 0, nil)
      new_live[key], values[i] = b, b
    end
    for _, t in ipairs{ live, dead } do    -- every other value is a destroyed body's
      for key, b in pairs(t) do
        if not new_live[key] then new_dead[key] = b end
      end
    end
    return new_live, new_dead, values
  end

  -- Whether the world of pointer p holds exactly the list's bodies, and how many it holds.
  local function matches(p, list)
    local n, same = C.rg_world_body_count(p), true
    if n ~= #list.entries then same = false end
    for _, e in ipairs(list.entries) do
      if C.rg_body_is_valid(p, e[1]) == 0 then same = false end
    end
    return same, n
  end

  -- After the library restored: the world's tables become the new ones, and the list's
  -- bodies take their saved serials and names.
  local function commit(w, p, list, new_live, new_dead, values)
    w[W_LIVE], w[W_DEAD], w[W_SERIAL] = new_live, new_dead, list.next_serial
    for i, e in ipairs(list.entries) do
      local b = values[i]
      rawset(b, B_SERIAL, e[2])   -- bodies have no fields to set from outside
      rawset(b, B_NAME, e[3])
      if C.rg_body_get_type(p, e[1], i32) == 0 then rawset(b, B_TYPE, i32[0]) end
    end
  end

  function World.restore(w, ...)
    local p = open_world(w)
    local s = ...
    if type(s) ~= "string" then typeerror(2, "string", s, select("#", ...) >= 1) end
    local list, at = read(s)
    local new_live, new_dead, values = prepare(w, list)
    -- The library checks its snapshot; whether the list names the bodies it holds shows
    -- only once it is loaded, so the world's state is kept to put back.
    local backup = library_snapshot(p, "restore")
    local st = C.rg_world_restore(p, ffi.cast("const uint8_t *", s) + at, #s - at)
    if st ~= 0 then status_error(p, st, "restore") end
    local same, n = matches(p, list)
    if not same then
      st = C.rg_world_restore(p, ffi.cast("const uint8_t *", backup), #backup)
      if st ~= 0 then status_error(p, st, "restore (putting the world back)") end
      raise(("restore: the snapshot's body list does not match its world " ..
             "(%d bodies listed, %d in the world)"):format(#list.entries, n))
    end
    commit(w, p, list, new_live, new_dead, values)
  end

  -- Kept states, as lua/lsnapshot.c has them: the library's (rg_world_save_slot), slot k in
  -- [0, 64), each with the body list of the moment, kept here by world and slot.
  local kept = setmetatable({}, { __mode = "k" })

  local function slot_of(k, what, given)
    if type(k) ~= "number" then typeerror(2, "number", k, given) end
    if k ~= math.floor(k) or k < 0 or k >= C.RG_MAX_SLOTS then
      raise(("bad argument #2 to '%s' (slot must be in [0, 64))"):format(what))
    end
    return k
  end

  function World.save_slot(w, ...)
    local p = open_world(w)
    local k = slot_of((...), "save_slot", select("#", ...) >= 1)
    local list = list_of(w)
    local st = C.rg_world_save_slot(p, k)
    if st ~= 0 then status_error(p, st, "save_slot") end
    kept[w] = kept[w] or {}
    kept[w][k] = list
  end

  function World.restore_slot(w, ...)
    local p = open_world(w)
    local k = slot_of((...), "restore_slot", select("#", ...) >= 1)
    local list = kept[w] and kept[w][k]
    if list == nil then raise(("restore_slot: slot %d is empty"):format(k)) end
    local new_live, new_dead, values = prepare(w, list)
    local st = C.rg_world_restore_slot(p, k)
    if st ~= 0 then status_error(p, st, "restore_slot") end
    if not matches(p, list) then   -- they were kept together: never
      raise(("restore_slot: slot %d's state does not match its body list"):format(k))
    end
    commit(w, p, list, new_live, new_dead, values)
  end

  function World.drop_slot(w, ...)
    local p = open_world(w)
    local k = slot_of((...), "drop_slot", select("#", ...) >= 1)
    local st = C.rg_world_drop_slot(p, k)
    if st ~= 0 then status_error(p, st, "drop_slot") end
    if kept[w] then kept[w][k] = nil end
  end

  function World.hash(w)
    local p = open_world(w)
    local st = C.rg_world_hash(p, hash)
    if st ~= 0 then status_error(p, st, "hash") end
    return ffi.cast(I64, hash[0])
  end
end
