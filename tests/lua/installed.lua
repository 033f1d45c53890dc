-- installed.lua: an installed module works.  `lua5.4 tests/lua/installed.lua rigid DIR` or
-- `luajit tests/lua/installed.lua rigid_jit DIR`: require finds the module under DIR (the
-- installed tree, not the source tree), and a body falls as semi-implicit Euler says
-- (after one step of dt, vy = g dt exactly: both are small powers of two).
local name, dir = ...
local rigid = require(name)
local path = package.searchpath(name, name == "rigid" and package.cpath or package.path)
assert(path and path:sub(1, #dir) == dir, "required from " .. tostring(path) .. ", not from " .. dir)
local w = rigid.world{ gravity = { 0, -8 } }
local b = w:body{ y = 1 }
w:step(0.125)
local _, vy = b:velocity()
assert(vy == -1, "vy after one step: " .. vy)
print(("ok    require %q from %s: rigid %s, rg_real of %d bytes"):format(name, path, rigid.version,
                                                                       rigid.real_size))
