# The Lua binding (build/rigid.so), the sandboxed host (build/rigid), their tests, the
# call-cost bench and the main job (make run: the platformer example).
LUA_PKG_CFLAGS := $(shell pkg-config --cflags lua5.4 2>/dev/null || echo -I/usr/include/lua5.4)
LUA_PKG_LIBS := $(shell pkg-config --libs lua5.4 2>/dev/null || echo -llua5.4)
LUA_BIN ?= lua5.4

LUA_MOD := $(B)/rigid.so
LUA_HOST := $(B)/rigid
LUA_HOST_SRC := lua/host.c lua/lsandbox.c lua/llong.c lua/lcount.c lua/lpattern.c lua/lutf8.c lua/lsvg.c
LUA_HOST_OBJ := $(patsubst lua/%.c,$(B)/lua/%.o,$(LUA_HOST_SRC))
# The binding: checks, world, body, springs, events and queries, registration.
LUA_BIND_SRC := lua/lcheck.c lua/lworld.c lua/lbody.c lua/lspring.c lua/lquery.c lua/lrigid.c
LUA_BIND_OBJ := $(patsubst lua/%.c,$(B)/lua/%.o,$(LUA_BIND_SRC))
LUA_PATFUZZ := $(B)/lua/pattern_fuzz

ALL_TARGETS += $(LUA_MOD) $(LUA_HOST)
TEST_RUNS += check-lua
# The Makefile expands `all:` and .PHONY before it includes the fragments.
.PHONY: check-lua bench-lua

$(B)/lua/%.o: lua/%.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LUA_PKG_CFLAGS) -Ilua -c $< -o $@

# The module exports luaopen_rigid and nothing else: the version script hides the rg_*
# symbols of the static library linked in.  Lua's own symbols come from the interpreter.
$(LUA_MOD): $(LUA_BIND_OBJ) $(LIB_A) lua/rigid.map
	$(CC) -shared -Wl,--version-script=lua/rigid.map $(LDFLAGS) -o $@ $(LUA_BIND_OBJ) $(LIB_A) $(LDLIBS)

$(LUA_HOST): $(LUA_HOST_OBJ) $(LUA_BIND_OBJ) $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $(LUA_HOST_OBJ) $(LUA_BIND_OBJ) $(LIB_A) $(LUA_PKG_LIBS) $(LDLIBS)

# The bounded pattern matcher checked against stock Lua's on random cases.
$(LUA_PATFUZZ): tests/lua/pattern_fuzz.c $(B)/lua/lpattern.o
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LUA_PKG_CFLAGS) -Ilua $(LDFLAGS) -o $@ $< $(B)/lua/lpattern.o $(LUA_PKG_LIBS) $(LDLIBS)

# Every Lua test: the API tests through the host and through stock lua5.4, the hostile
# scripts, every example (with its picture) and the pattern matcher against stock Lua.
check-lua: $(LUA_MOD) $(LUA_HOST) $(LUA_PATFUZZ)
	@echo "== tests/lua"
	$(LUA_BIN) tests/lua/run.lua --host $(LUA_HOST) --module-dir $(B) --lua $(LUA_BIN) \
	  --out $(B)/lua-tests --fuzz $(LUA_PATFUZZ) --lua-env "$(FFI_ENV)"

# The main job (make run): the platformer, a line per second, its picture in $(B)/run.svg.
run-main: $(LUA_HOST)
	@$(LUA_HOST) lua/examples/platformer.lua --svg $(B)/run.svg

# Cost of one Lua call into the binding, in stock lua5.4 and in the host.
bench: bench-lua
bench-lua: $(LUA_MOD) $(LUA_HOST)
	@echo "== Lua call cost (stock $(LUA_BIN) + $(LUA_MOD))"
	@LUA_CPATH="$(B)/?.so" $(FFI_ENV) $(LUA_BIN) lua/bench_calls.lua
	@echo "== Lua call cost (host $(LUA_HOST), sandboxed, --budget 0)"
	@$(LUA_HOST) lua/bench_calls.lua --budget 0
	@echo "== Lua call cost (host $(LUA_HOST), sandboxed, budget hooks on)"
	@$(LUA_HOST) lua/bench_calls.lua --budget 100000000000

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
