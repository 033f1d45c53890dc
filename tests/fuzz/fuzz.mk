# The libFuzzer harnesses (make fuzz) and the pending reliability tests (make pending).
#   make fuzz                 builds tests/fuzz/fuzz_*.c with clang under ASan + UBSan (the
#                             library and the Lua host objects too) and runs each harness for
#                             FUZZ_SECONDS (default 60) from its seed corpus (for fuzz_lua
#                             also every hostile script of tests/lua/hostile)
#   make fuzz FUZZ=api        one harness (fuzz_api, fuzz_lua)
#   make pending              tests/fuzz/pending/test_*.c: library findings awaiting their fix
#                             (each fails today; they move into tests/ when the fix lands)
# New inputs a run finds go to build/fuzz/corpus/<harness>, crashes to build/fuzz/artifacts.
FUZZ_CC ?= clang
FUZZ_SECONDS ?= 60
FUZZ ?= api lua
FUZZ_B := build/fuzz$(if $(filter double,$(REAL)),-double)
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g
PENDING_B := build/pending$(if $(filter double,$(REAL)),-double)

# Known library bugs whose sanitizer report would stop every run before the fix lands, as
# per-file flags for the sanitized builds (make sanitize CC=clang, make fuzz); each names the
# test that reproduces it, and goes when the fix lands.
# (none open: restore.c's pool check computes a forged free-list index in 64 bits now)
SAN_KNOWN_VARS :=

.PHONY: fuzz fuzz-build pending pending-build
fuzz:
	@tools/install-deps.sh --fuzz
	@$(MAKE) --no-print-directory fuzz-build B=$(FUZZ_B) CC=$(FUZZ_CC) REAL=$(REAL) OPT=-O1 \
	  $(SAN_KNOWN_VARS) EXTRA_CFLAGS="$(FUZZ_SAN) -fsanitize=fuzzer-no-link" \
	  EXTRA_LDFLAGS="$(FUZZ_SAN)"
	@fail=0; for h in $(FUZZ); do \
	  mkdir -p $(FUZZ_B)/corpus/$$h $(FUZZ_B)/artifacts; \
	  echo "== fuzz_$$h for $(FUZZ_SECONDS) s"; \
	  $(FUZZ_B)/fuzz/fuzz_$$h -max_total_time=$(FUZZ_SECONDS) -timeout=120 -max_len=4096 \
	    -print_final_stats=1 -artifact_prefix=$(FUZZ_B)/artifacts/$$h- \
	    $$(test -f tests/fuzz/$$h.dict && echo -dict=tests/fuzz/$$h.dict) \
	    $(FUZZ_B)/corpus/$$h tests/fuzz/corpus/$$h $$(test $$h = lua && echo tests/lua/hostile) \
	    > $(FUZZ_B)/fuzz_$$h.log 2>&1 \
	    || { fail=1; echo "fuzz_$$h FAILED (log: $(FUZZ_B)/fuzz_$$h.log)"; tail -n 40 $(FUZZ_B)/fuzz_$$h.log; }; \
	  grep -E 'DONE|^stat::number_of_executed_units|^stat::peak_rss_mb' $(FUZZ_B)/fuzz_$$h.log || true; \
	done; \
	if [ $$fail -ne 0 ]; then echo "make fuzz: FAILED"; exit 1; fi; echo "make fuzz: no findings"

# Only in the submake above, where B is $(FUZZ_B) and CC is clang.  A new harness (the
# snapshot reader, fuzz_snapshot.c over rg_world_restore, once snapshots exist) is a file
# tests/fuzz/fuzz_<name>.c, a rule below, its name in FUZZ and its seeds in corpus/<name>/.
fuzz-build: $(patsubst %,$(B)/fuzz/fuzz_%,$(FUZZ))

$(B)/fuzz/fuzz_api: tests/fuzz/fuzz_api.c tests/fuzz/fuzz_api_model.c tests/fuzz/fuzz_api.h $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -fsanitize=fuzzer $(LDFLAGS) -o $@ tests/fuzz/fuzz_api.c tests/fuzz/fuzz_api_model.c \
	  $(LIB_A) $(LDLIBS)

FUZZ_LUA_OBJ := $(B)/lua/lsandbox.o $(B)/lua/llong.o $(B)/lua/lcount.o $(B)/lua/lpattern.o $(B)/lua/lutf8.o $(LUA_BIND_OBJ)
$(B)/fuzz/fuzz_lua: tests/fuzz/fuzz_lua.c $(FUZZ_LUA_OBJ) $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LUA_PKG_CFLAGS) -Ilua -fsanitize=fuzzer $(LDFLAGS) -o $@ $< \
	  $(FUZZ_LUA_OBJ) $(LIB_A) $(LUA_PKG_LIBS) $(LDLIBS)

# The pending tests run against the library built by clang with ASan + UBSan and without the
# SAN_KNOWN exceptions, so that a finding UBSan reports fails its test too.  A failing cmocka
# test skips its cleanup: leaks are not reported.
PENDING_SRC := $(wildcard tests/fuzz/pending/test_*.c)
pending:
	@tools/install-deps.sh --fuzz
	@$(MAKE) --no-print-directory pending-build B=$(PENDING_B) CC=$(FUZZ_CC) REAL=$(REAL) OPT=-O1 \
	  EXTRA_CFLAGS="$(FUZZ_SAN)" EXTRA_LDFLAGS="$(FUZZ_SAN)"
	@fail=0; for t in $(patsubst tests/fuzz/pending/%.c,$(PENDING_B)/pending/%,$(PENDING_SRC)); do \
	  echo "== $$t"; ASAN_OPTIONS=detect_leaks=0 $$t || fail=1; done; \
	if [ $$fail -ne 0 ]; then echo "make pending: some findings are still open"; exit 1; fi

pending-build: $(patsubst tests/fuzz/pending/%.c,$(B)/pending/%,$(PENDING_SRC))

$(B)/pending/%: tests/fuzz/pending/%.c tests/testutil.h $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -Itests $(LDFLAGS) -o $@ $< $(LIB_A) $(CMOCKA_LIBS) $(LDLIBS)
