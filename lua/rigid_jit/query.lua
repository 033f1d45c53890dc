-- rigid_jit/query.lua: what the LuaJIT binding reads out of a world after a step, as
-- lua/lquery.c does: contact events (world:events) and the queries (world:raycast,
-- raycast_all, query_aabb, query_point, cast_circle, cast_box, stopped).  rigid_jit.lua calls the
-- function this returns with its core (World, open_world, push_body); it returns
-- { pushhit = f } for rigid_jit/contact.lua.
local ffi = require "ffi"
local lib = require "rigid_jit.ffi"
local check = require "rigid_jit.check"

local C, V = lib.C, lib.V
local real1, real2, real4, optmask = check.real1, check.real2, check.real4, check.optmask
local status_error = check.status_error

return function(core)
  local World, open_world, push_body = core.World, core.open_world, core.push_body

  -- Scratch arrays that grow to the largest count seen.
  local function grow(buf, cap, n, ctype)
    if n > cap then return ffi.new(ctype, n), n end
    return buf, cap
  end

  local events, events_cap = nil, 0

  -- The events of the last step, or of every step of the last advance.
  function World.events(w)
    local p = open_world(w)
    local n = C.rg_world_get_contact_events(p, nil, 0)
    if n < 0 then status_error(p, n, "events") end
    events, events_cap = grow(events, events_cap, n, "rg_contact_event[?]")
    if n > 0 then n = C.rg_world_get_contact_events(p, events, n) end
    local out = {}
    for i = 0, n - 1 do
      local e = events[i]
      out[i + 1] = { kind = e.kind == C.RG_CONTACT_BEGIN and "begin" or "end",
                     a = push_body(w, e.a), b = push_body(w, e.b),
                     nx = e.normal.x, ny = e.normal.y, x = e.point.x, y = e.point.y,
                     depth = e.depth, speed = e.speed, sensor = e.sensor ~= 0 }
    end
    return out
  end

  -- A ray hit as { body, x, y, nx, ny, fraction }.
  local function pushhit(w, e)
    return { body = push_body(w, e.body), x = e.point.x, y = e.point.y,
             nx = e.normal.x, ny = e.normal.y, fraction = e.fraction }
  end

  -- The returns of world:raycast, cast_circle and cast_box for a query that returned r:
  -- body, x, y, nx, ny, fraction, or nil.  (Each checks r itself: an error raised here,
  -- below a tail call, could not find the line that called it.)
  local hit = ffi.new("rg_ray_hit[1]")
  local function returnhit(w, r)
    if r == 0 then return nil end
    local e = hit[0]
    return push_body(w, e.body), e.point.x, e.point.y, e.normal.x, e.normal.y, e.fraction
  end

  function World.raycast(w, ...)
    local p = open_world(w)
    local ox, oy, dx, dy = real4(2, ...)
    local r = V.rg_world_raycast(p, ox, oy, dx, dy, optmask(6, select(5, ...)), hit)
    if r < 0 then status_error(p, r, "raycast") end
    return returnhit(w, r)
  end

  function World.cast_circle(w, ...)
    local p = open_world(w)
    local radius = real1(2, ...)
    local ox, oy, dx, dy = real4(3, select(2, ...))
    local mask = optmask(7, select(6, ...))
    local r = V.rg_world_cast_shape(p, C.RG_SHAPE_CIRCLE, radius, 0, ox, oy, dx, dy, mask, hit)
    if r < 0 then status_error(p, r, "cast_circle") end
    return returnhit(w, r)
  end

  function World.cast_box(w, ...)
    local p = open_world(w)
    local hw, hh = real2(2, ...)
    local ox, oy, dx, dy = real4(4, select(3, ...))
    local mask = optmask(8, select(7, ...))
    local r = V.rg_world_cast_shape(p, C.RG_SHAPE_AABB, hw, hh, ox, oy, dx, dy, mask, hit)
    if r < 0 then status_error(p, r, "cast_box") end
    return returnhit(w, r)
  end

  local hits, hits_cap = nil, 0

  function World.raycast_all(w, ...)
    local p = open_world(w)
    local ox, oy, dx, dy = real4(2, ...)
    local mask = optmask(6, select(5, ...))
    local n = V.rg_world_raycast_all(p, ox, oy, dx, dy, mask, nil, 0)
    if n < 0 then status_error(p, n, "raycast_all") end
    hits, hits_cap = grow(hits, hits_cap, n, "rg_ray_hit[?]")
    if n > 0 then n = V.rg_world_raycast_all(p, ox, oy, dx, dy, mask, hits, n) end
    local out = {}
    for i = 0, n - 1 do out[i + 1] = pushhit(w, hits[i]) end
    return out
  end

  local found, found_cap = nil, 0

  -- The first n bodies of found as an array of body values.
  local function found_list(w, n)
    local out = {}
    for i = 0, n - 1 do out[i + 1] = push_body(w, found[i]) end
    return out
  end

  -- A body list as an array of body values: list(p, a, b, c, d, mask, out, cap) counts with
  -- (nil, 0), then copies.  It may raise, so its callers keep their frame (no tail call).
  local function body_list(w, p, what, list, a, b, c, d, mask)
    local n = list(p, a, b, c, d, mask, nil, 0)
    if n < 0 then status_error(p, n, what) end
    found, found_cap = grow(found, found_cap, n, "rg_body[?]")
    if n > 0 then n = list(p, a, b, c, d, mask, found, n) end
    return found_list(w, n)
  end

  local function list_point(p, x, y, _, _, mask, out, cap) return V.rg_world_query_point(p, x, y, mask, out, cap) end
  local function list_stopped(p, _, _, _, _, _, out, cap) return C.rg_world_get_stopped(p, out, cap) end

  function World.query_aabb(w, ...)
    local p = open_world(w)
    local x0, y0, x1, y1 = real4(2, ...)
    local out = body_list(w, p, "query_aabb", V.rg_world_query_aabb, x0, y0, x1, y1, optmask(6, select(5, ...)))
    return out
  end

  function World.query_point(w, ...)
    local p = open_world(w)
    local x, y = real2(2, ...)
    local out = body_list(w, p, "query_point", list_point, x, y, nil, nil, optmask(4, select(3, ...)))
    return out
  end

  function World.stopped(w)
    local out = body_list(w, open_world(w), "stopped", list_stopped)
    return out
  end

  return { pushhit = pushhit, grow = grow }
end
