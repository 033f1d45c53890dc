-- rigid_jit/contact.lua: the gameplay methods of a body in the LuaJIT binding, as
-- lua/lcontact.c has them: body:contacts(), body:pass_through(other) and the character
-- mover body:move(tx, ty [, options]).  (body:set_one_way and body:one_way are getters and
-- setters like the others, in rigid_jit.lua.)  rigid_jit.lua calls the function this
-- returns with its core and the query module's helpers (it returns nothing).
local ffi = require "ffi"
local lib = require "rigid_jit.ffi"
local check = require "rigid_jit.check"

local C, V = lib.C, lib.V
local argerror, typeerror, status_error = check.argerror, check.typeerror, check.status_error
local BODY = check.BODY

local RESPONSES = { "slide", "touch", "cross" }
local MOVE_OPTIONS = { "mask", "response" }
-- Room for the hits of one move: SLIDE meets at most 8 surfaces and TOUCH one; a CROSS that
-- crosses more is made again with room for all (as in lua/lcontact.c).
local HITS = 16

return function(core, query)
  local Body, body_wh, body_handle, push_body = core.Body, core.body_wh, core.body_handle,
                                               core.push_body
  local B_BOX, B_H, B_WORLD = core.B_BOX, core.B_H, core.B_WORLD
  local pushhit, grow = query.pushhit, query.grow

  local contacts, contacts_cap = nil, 0

  -- { { other, nx, ny, x, y, separation, normal_impulse, tangent_impulse, sensor }... }
  -- after the last step, in ascending order of other.
  function Body.contacts(b)
    local p, h = body_wh(b)
    local n = C.rg_body_get_contacts(p, h, nil, 0)
    if n < 0 then status_error(p, n, "contacts") end
    contacts, contacts_cap = grow(contacts, contacts_cap, n, "rg_contact[?]")
    if n > 0 then n = C.rg_body_get_contacts(p, h, contacts, n) end
    local w, out = b[B_WORLD], {}
    for i = 0, n - 1 do
      local c = contacts[i]
      out[i + 1] = { other = push_body(w, c.other), nx = c.normal.x, ny = c.normal.y,
                     x = c.point.x, y = c.point.y, separation = c.separation,
                     normal_impulse = c.normal_impulse, tangent_impulse = c.tangent_impulse,
                     sensor = c.sensor ~= 0 }
    end
    return out
  end

  -- The checks in lua/lcontact.c's order: self, other, the same world, then an open world.
  function Body.pass_through(b, ...)
    local other = ...
    if getmetatable(b) ~= BODY then typeerror(1, BODY, b) end
    if getmetatable(other) ~= BODY then typeerror(2, BODY, other, select("#", ...) >= 1) end
    if not rawequal(other[B_BOX], b[B_BOX]) then argerror(2, "a body of the same world") end
    local p, h = body_wh(b)
    local st = C.rg_body_pass_through(p, h, body_handle(other))
    if st ~= 0 then status_error(p, st, "pass_through") end
  end

  local hits, hits_cap = ffi.new("rg_ray_hit[?]", HITS), HITS
  local start, pos, count = ffi.new("rg_vec2[1]"), ffi.new("rg_vec2[1]"), ffi.new("int32_t[1]")

  -- x, y, { { body, x, y, nx, ny, fraction }... }: where the body stopped and the surfaces
  -- met.  A CROSS lands on its target exactly, so one back to the start restores the
  -- position bit for bit before the second try, and keeps the position rendering
  -- interpolates from.
  function Body.move(b, ...)
    local what = "move"
    local p, h = body_wh(b)
    local tx, ty = check.real2(2, ...)
    local opts, mask, response = select(3, ...), 0xFFFFFFFF, C.RG_MOVE_SLIDE
    if opts ~= nil then
      check.checktable(4, opts, true)
      check.option_names(opts, MOVE_OPTIONS, what)
      mask = check.option_integer(opts, "mask", what, 0, 0xFFFFFFFF) or mask
      response = check.option_enum(opts, "response", what, RESPONSES) or response
    end
    local st = C.rg_body_get_position(p, h, start)
    if st ~= 0 then status_error(p, st, what) end
    st = V.rg_body_move(p, h, tx, ty, mask, response, pos, hits, hits_cap, count)
    if st ~= 0 then status_error(p, st, what) end
    local n = count[0]
    if n > hits_cap then
      st = V.rg_body_move(p, h, start[0].x, start[0].y, 0, C.RG_MOVE_CROSS, nil, nil, 0, nil)
      if st ~= 0 then status_error(p, st, what) end
      hits, hits_cap = grow(hits, hits_cap, n, "rg_ray_hit[?]")
      st = V.rg_body_move(p, h, tx, ty, mask, response, pos, hits, hits_cap, count)
      if st ~= 0 then status_error(p, st, what) end
      n = math.min(count[0], hits_cap)   -- the same path crosses the same shapes
    end
    local w, out = b[B_WORLD], {}
    for i = 0, n - 1 do out[i + 1] = pushhit(w, hits[i]) end
    return pos[0].x, pos[0].y, out
  end
end
