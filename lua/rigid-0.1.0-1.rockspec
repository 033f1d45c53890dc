-- The Lua 5.4 module of rigid as a rock: `luarocks make lua/rigid-0.1.0-1.rockspec` from the
-- top of the source tree builds build/rock/rigid.so with the project's Makefile (its flags:
-- C99, -ffp-contract=off for bit-identical results) and installs it as `rigid`.
rockspec_format = "3.0"
package = "rigid"
version = "0.1.0-1"
source = {
   url = "git+file:///dev/null",   -- luarocks make builds the tree it runs in
}
description = {
   summary = "2D game physics (translation only) in C99, for Lua 5.4",
   detailed = [[
      rigid: circles and axis-aligned boxes, static, kinematic and dynamic bodies, the
      forces gameplay uses, four integrators behind a fixed-step accumulator, contact
      events, queries and sleeping.  require "rigid".
   ]],
   license = "MIT",
}
dependencies = {
   "lua >= 5.4, < 5.5",
}
build = {
   type = "make",
   build_target = "rock-build",
   build_variables = {
      B = "build/rock",
      LUA_PKG_CFLAGS = "-I$(LUA_INCDIR)",
   },
   install_target = "rock-install",
   install_variables = {
      B = "build/rock",
      ROCK_LIBDIR = "$(LIBDIR)",
   },
}
