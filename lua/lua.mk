# The Lua binding (build/rigid.so), the sandboxed host (build/rigid), the LuaJIT binding
# (lua/rigid_jit.lua, nothing to build), their tests, the call-cost bench, the main job
# (make run: the platformer example), their part of make install and the rock.
LUA_PKG_CFLAGS := $(shell pkg-config --cflags lua5.4 2>/dev/null || echo -I/usr/include/lua5.4)
LUA_PKG_LIBS := $(shell pkg-config --libs lua5.4 2>/dev/null || echo -llua5.4)
LUA_BIN ?= lua5.4
LUAJIT_BIN ?= luajit
LOVE_BIN ?= love

LUA_MOD := $(B)/rigid.so
LUA_HOST := $(B)/rigid
LUA_HOST_SRC := lua/host.c lua/lsandbox.c lua/llong.c lua/lcount.c lua/lpattern.c lua/lutf8.c \
                lua/lsvg.c lua/lsample.c lua/lhtml.c lua/lframes.c lua/lenc.c
# The replay viewer's page, compiled in as an array of lines (lua/viewer.mk).
LUA_VIEWER := $(B)/lua/lviewer_html.o
LUA_HOST_OBJ := $(patsubst lua/%.c,$(B)/lua/%.o,$(LUA_HOST_SRC)) $(LUA_VIEWER)
ZLIB_LIBS := $(shell pkg-config --libs zlib 2>/dev/null || echo -lz)
# The binding: checks, world, body, springs, events and queries, contacts, snapshots,
# registration.
LUA_BIND_SRC := lua/lcheck.c lua/lworld.c lua/lbody.c lua/lspring.c lua/lquery.c lua/lcontact.c \
                lua/lsnapshot.c lua/lrigid.c
LUA_BIND_OBJ := $(patsubst lua/%.c,$(B)/lua/%.o,$(LUA_BIND_SRC))
LUA_PATFUZZ := $(B)/lua/pattern_fuzz

ALL_TARGETS += $(LUA_MOD) $(LUA_HOST)
TEST_RUNS += check-lua check-ffi-cdef
# The Makefile expands `all:` and .PHONY before it includes the fragments.
.PHONY: check-lua bench-lua check-ffi-cdef ffi-cdef

$(B)/lua/%.o: lua/%.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LUA_PKG_CFLAGS) -Ilua -c $< -o $@

# The module exports luaopen_rigid and nothing else: the version script hides the rg_*
# symbols of the static library linked in.  Lua's own symbols come from the interpreter.
$(LUA_MOD): $(LUA_BIND_OBJ) $(LIB_A) lua/rigid.map
	$(CC) -shared -Wl,--version-script=lua/rigid.map $(LDFLAGS) -o $@ $(LUA_BIND_OBJ) $(LIB_A) $(LDLIBS)

$(LUA_HOST): $(LUA_HOST_OBJ) $(LUA_BIND_OBJ) $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $(LUA_HOST_OBJ) $(LUA_BIND_OBJ) $(LIB_A) $(LUA_PKG_LIBS) $(ZLIB_LIBS) $(LDLIBS)


# The bounded pattern matcher checked against stock Lua's on random cases.
$(LUA_PATFUZZ): tests/lua/pattern_fuzz.c $(B)/lua/lpattern.o
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LUA_PKG_CFLAGS) -Ilua $(LDFLAGS) -o $@ $< $(B)/lua/lpattern.o $(LUA_PKG_LIBS) $(LDLIBS)

# Every Lua test: the API tests through the host, through stock lua5.4 and through the
# LuaJIT binding, the hostile scripts, every example (with its picture), the LOVE game and
# the pattern matcher against stock Lua.
check-lua: $(LUA_MOD) $(LUA_HOST) $(LUA_PATFUZZ) $(LIB_SO)
	@echo "== tests/lua"
	$(LUA_BIN) tests/lua/run.lua --host $(LUA_HOST) --module-dir $(B) --lua $(LUA_BIN) \
	  --out $(B)/lua-tests --fuzz $(LUA_PATFUZZ) --lua-env "$(FFI_ENV)" \
	  --library $(LIB_SO) --luajit "$(LUAJIT_BIN)" --love "$(LOVE_BIN)"

# The LuaJIT binding declares the header as the preprocessor reads it; `make ffi-cdef`
# rewrites that block after a change of include/rigid.h, and the test fails until then.
check-ffi-cdef:
	@echo "== lua/rigid_jit/ffi.lua against include/rigid.h"
	@CC="$(CC)" $(LUA_BIN) tools/ffi_cdef.lua --check lua/rigid_jit/ffi.lua

ffi-cdef:
	CC="$(CC)" $(LUA_BIN) tools/ffi_cdef.lua --update lua/rigid_jit/ffi.lua

# The examples' pictures say what the world was at the moment they show: bodies alive then,
# contacts where bodies touch, labels off the bodies, text inside the picture.
TEST_RUNS += check-pictures
.PHONY: check-pictures
check-pictures: $(LUA_HOST)
	@echo "== tests/pictures/check_svg.py"
	$(PYTHON) tests/pictures/check_svg.py --host $(LUA_HOST) --out $(B)/picture-check

# The main job (make run): the platformer, a line per second, its picture in $(B)/run.svg
# and its replay in $(B)/run.html.
run-main: $(LUA_HOST)
	@$(LUA_HOST) lua/examples/platformer.lua --svg $(B)/run.svg --html $(B)/run.html

# Cost of one Lua call into the binding, in stock lua5.4, in the host and in LuaJIT.
bench: bench-lua
bench-lua: $(LUA_MOD) $(LUA_HOST) $(LIB_SO)
	@echo "== Lua call cost (stock $(LUA_BIN) + $(LUA_MOD))"
	@LUA_CPATH="$(B)/?.so" $(FFI_ENV) $(LUA_BIN) lua/bench_calls.lua
	@echo "== Lua call cost (host $(LUA_HOST), sandboxed, --budget 0)"
	@$(LUA_HOST) lua/bench_calls.lua --budget 0
	@echo "== Lua call cost (host $(LUA_HOST), sandboxed, budget hooks on)"
	@$(LUA_HOST) lua/bench_calls.lua --budget 100000000000
	@echo "== what the work the sandbox charges by size costs (host $(LUA_HOST), --budget 0)"
	@$(LUA_HOST) lua/bench_sandbox.lua --budget 0
	@if command -v $(LUAJIT_BIN) >/dev/null; then \
	  echo "== Lua call cost ($(LUAJIT_BIN) + lua/rigid_jit.lua + $(LIB_SO))"; \
	  LUA_PATH="lua/?.lua;;" RIGID_LIBRARY=$(LIB_SO) $(FFI_ENV) $(LUAJIT_BIN) lua/bench_calls.lua; \
	else echo "== no $(LUAJIT_BIN): the LuaJIT call cost is not measured"; fi

-include $(LUA_HOST_OBJ:.o=.d) $(LUA_BIND_OBJ:.o=.d)

# The README's Lua example, extracted and run in the host, so it stays true.
TEST_RUNS += check-readme-lua
.PHONY: check-readme-lua
$(B)/readme_example.lua: README.md
	@mkdir -p $(@D)
	awk '/^<!-- example:lua -->/{on=1;next} on&&/^```lua/{inb=1;next} inb&&/^```/{exit} inb{print}' $< > $@
	@test -s $@ || { echo "README.md has no Lua example"; exit 1; }

check-readme-lua: $(LUA_HOST) $(B)/readme_example.lua
	@echo "== README Lua example"
	$(LUA_HOST) $(B)/readme_example.lua --seconds 4 --svg $(B)/readme_example.svg

# ---------------------------------------------------------------- install, luarocks
# make install adds the Lua 5.4 module, the LuaJIT binding and the host.  Only the float
# build installs them: they have one name each, and the float build is the usual one (the
# LuaJIT binding loads the double library too, by RIGID_LIBRARY).
LUA_CMOD_DIR ?= $(PREFIX)/lib/lua/5.4
LUA_LMOD_DIR ?= $(PREFIX)/share/lua/5.1
LUA_JIT_FILES := rigid_jit.lua rigid_jit/ffi.lua rigid_jit/check.lua rigid_jit/query.lua \
                 rigid_jit/contact.lua rigid_jit/snapshot.lua
.PHONY: install-lua uninstall-lua rock-build rock-install check-rock
ifeq ($(REAL),float)
install: install-lua
uninstall: uninstall-lua
endif

install-lua: $(LUA_MOD) $(LUA_HOST)
	install -d $(DESTDIR)$(LUA_CMOD_DIR) $(DESTDIR)$(LUA_LMOD_DIR)/rigid_jit $(DESTDIR)$(PREFIX)/bin
	install -m 755 $(LUA_MOD) $(DESTDIR)$(LUA_CMOD_DIR)/rigid.so
	for f in $(LUA_JIT_FILES); do install -m 644 lua/$$f $(DESTDIR)$(LUA_LMOD_DIR)/$$f || exit 1; done
	install -m 755 $(LUA_HOST) $(DESTDIR)$(PREFIX)/bin/rigid

# The directory rigid_jit/ is the binding's own; the others are shared (see uninstall).
uninstall-lua:
	rm -f $(DESTDIR)$(LUA_CMOD_DIR)/rigid.so $(addprefix $(DESTDIR)$(LUA_LMOD_DIR)/,$(LUA_JIT_FILES)) \
	  $(DESTDIR)$(PREFIX)/bin/rigid
	rmdir $(DESTDIR)$(LUA_LMOD_DIR)/rigid_jit 2>/dev/null || true

# luarocks make lua/rigid-$(VERSION)-1.rockspec: the rock builds with `make rock-build` (in
# build/rock, against the rock's Lua headers) and installs with `make rock-install`.
rock-build: $(LUA_MOD)
rock-install: $(LUA_MOD)
	install -d $(ROCK_LIBDIR)
	install -m 755 $(LUA_MOD) $(ROCK_LIBDIR)/rigid.so

# The rock into a temporary tree, and the module required from there.  The rock's make
# must not inherit this make's variables (a sanitizer build's flags, its B): neither through
# MAKEFLAGS nor through the environment, where make exports the command line's (a
# sanitizer run's EXTRA_LDFLAGS hold clang's -shared-libasan, which luarocks's gcc refuses).
ifeq ($(REAL),float)
TEST_RUNS += check-rock
endif
check-rock:
	@echo "== luarocks make lua/rigid-$(VERSION)-1.rockspec"
	@if ! command -v luarocks >/dev/null; then \
	  echo "skip  the rock: no luarocks (tools/install-deps.sh installs it)"; exit 0; fi; \
	 tree=$(B)/rock-tree; rm -rf $$tree; \
	 env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u EXTRA_CFLAGS -u EXTRA_LDFLAGS -u OPT luarocks --lua-version 5.4 --tree $$tree \
	   make lua/rigid-$(VERSION)-1.rockspec > $(B)/rock.log 2>&1 \
	   || { cat $(B)/rock.log; echo "FAIL  luarocks make"; exit 1; }; \
	 LUA_CPATH="$$tree/lib/lua/5.4/?.so" $(FFI_ENV) $(LUA_BIN) tests/lua/installed.lua rigid $$tree
