# rigid: build, test, run, bench, charts, sanitize.
#   make                 build/librigid.a and build/librigid.so (float build)
#   make test            build everything and run every test (installs what is missing)
#   make run             the main job
#   make REAL=double     the double-precision build, in build/double/ (librigid-double)
#   make sanitize        the tests under AddressSanitizer + UndefinedBehaviorSanitizer
#                        (CC=clang for clang's; each compiler builds in its own folder)
#   make fuzz            the libFuzzer harnesses of tests/fuzz, FUZZ_SECONDS each (clang)
#   make tsan            the threaded tests under ThreadSanitizer (clang)
#   make test-aarch64, test-armhf, test-i386, test-s390x   the C tests built for that
#                        machine, run under qemu-user (32-bit ARM and x86; s390x is
#                        big-endian)
#   make test-tcc        the library and the C tests built by tcc (tools/tcc.mk)
#   make install PREFIX=/usr/local   (and make uninstall; DESTDIR for staging)
REAL ?= float
PREFIX ?= /usr/local
CC ?= cc
PYTHON ?= python3

# The double build has names of its own (library, SONAME, pc), so that no float program
# ever loads it, nor a double program the float library.
ifeq ($(REAL),double)
REAL_FLAGS := -DRG_DOUBLE
DEFAULT_B := build/double
LIB_NAME := rigid-double
else ifeq ($(REAL),float)
REAL_FLAGS :=
DEFAULT_B := build
LIB_NAME := rigid
else
$(error REAL must be float or double)
endif
B ?= $(DEFAULT_B)

OPT ?= -O2
# Every operation on rg_real must round to rg_real (src/vec2.h refuses a build that keeps
# excess precision, FLT_EVAL_METHOD > 0).  32-bit x86 compilers do float arithmetic on the
# x87 by default (FLT_EVAL_METHOD 2): other bits than every other machine's, and decisions
# made on exact comparisons (a graze, a seam) go otherwise; SSE2 arithmetic rounds as
# x86-64 does.  gcc for s390x evaluates float in double under -std=c99 (FLT_EVAL_METHOD 1)
# though the machine has float operations, which -fexcess-precision=fast uses.
CC_MACROS := $(shell $(CC) -dM -E -x c /dev/null 2>/dev/null)
FPMATH := $(if $(findstring __i386__,$(CC_MACROS)),$(if $(findstring __SSE2_MATH__,$(CC_MACROS)),,-msse2 -mfpmath=sse))
FLT_EVAL := $(shell printf '\043include <float.h>\nFLT_EVAL_METHOD\n' | \
              $(CC) -std=c99 $(FPMATH) -E -P -x c - 2>/dev/null | tail -n 1)
FPMATH += $(if $(filter 1 2,$(FLT_EVAL)),-fexcess-precision=fast)
WARN := -Wall -Wextra -Wpedantic -Werror -Wshadow -Wundef -Wwrite-strings \
        -Wmissing-prototypes -Wstrict-prototypes -Wdouble-promotion -Wcast-qual \
        -Wpointer-arith -Wvla
CFLAGS := -std=c99 $(OPT) $(FPMATH) -ffp-contract=off -fPIC -fvisibility=hidden $(WARN) $(REAL_FLAGS) \
          -Iinclude -Isrc -MMD -MP $(EXTRA_CFLAGS)
LDFLAGS := $(EXTRA_LDFLAGS)
LDLIBS := -lm -pthread

VERSION := 0.1.0
SONAME := lib$(LIB_NAME).so.0
LIB_SRC := $(wildcard src/*.c)
LIB_OBJ := $(patsubst src/%.c,$(B)/obj/%.o,$(LIB_SRC))
LIB_A := $(B)/lib$(LIB_NAME).a
LIB_SO := $(B)/lib$(LIB_NAME).so

CMOCKA_LIBS := -lcmocka
TEST_SRC := $(wildcard tests/test_*.c)
TEST_BINS := $(patsubst tests/%.c,$(B)/tests/%,$(TEST_SRC))

# Fragments append to these; they are included here, before any rule uses the lists
# (a prerequisite list is expanded when make reads the rule).
ALL_TARGETS := $(LIB_A) $(LIB_SO)
TEST_RUNS := check-c check-ffi check-readme check-exports check-modules check-install
.DEFAULT_GOAL := all
# Other machines, each a Debian cross gcc and its qemu-user (tools/install-deps.sh --cross):
# the snapshots across machines (tools/snapshot.mk) and make test-aarch64 / armhf / i386 /
# s390x.
CROSS_MACHINES := aarch64 armhf i386 s390x
CROSS_TESTS := $(patsubst %,test-%,$(CROSS_MACHINES))
CROSS_CC_aarch64 ?= aarch64-linux-gnu-gcc
CROSS_RUN_aarch64 ?= qemu-aarch64
CROSS_CC_armhf ?= arm-linux-gnueabihf-gcc
CROSS_RUN_armhf ?= qemu-arm
CROSS_CC_i386 ?= i686-linux-gnu-gcc
CROSS_RUN_i386 ?= qemu-i386
CROSS_CC_s390x ?= s390x-linux-gnu-gcc
CROSS_RUN_s390x ?= qemu-s390x
include $(sort $(wildcard lua/*.mk tools/*.mk tests/fuzz/*.mk))

.PHONY: all test test-all $(CROSS_TESTS) deps sanitize tsan memcheck install uninstall FORCE clean run run-main bench charts \
        $(TEST_RUNS)
all: $(ALL_TARGETS)

# The main job; a fragment defines run-main.  `bench` and `charts` gather prerequisites
# from the fragments (bench: bench-x, charts: charts-y), each with its own recipe.
run: deps
	@$(MAKE) --no-print-directory run-main

# ---------------------------------------------------------------- library
# SAN_KNOWN_<file> holds, in sanitized builds, the checks a known library bug in that file
# would trip before its fix lands (see tests/fuzz/fuzz.mk); empty otherwise.
$(B)/obj/%.o: src/%.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(SAN_KNOWN_$*) -c $< -o $@

$(LIB_A): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(LIB_SO): $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) $(LDFLAGS) -o $@ $^ $(LDLIBS)

# ---------------------------------------------------------------- tests
# The tests and the README's examples write their scenes in float constants (0.4f), so that
# the float and the double build start from the same numbers.  clang's -Wdouble-promotion
# flags such a constant passed as a double rg_real (gcc's does not flag constants); every
# place it flags there is one, so they build without that warning in clang's double build.
TEST_CFLAGS = $(if $(and $(CC_IS_CLANG),$(filter double,$(REAL))),-Wno-double-promotion)
$(B)/tests/%: tests/%.c $(wildcard tests/*.h) $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(TEST_CFLAGS) -Itests $(LDFLAGS) -o $@ $< $(LIB_A) $(CMOCKA_LIBS) $(LDLIBS)

# TEST_RUN: what runs each test program (qemu-user for make test-aarch64's and the others).
check-c: $(TEST_BINS)
	@fail=0; for t in $(TEST_BINS); do echo "== $$t"; $(TEST_RUN) $$t || fail=1; done; exit $$fail

# The C tests built for another machine with Debian's cross gcc (CROSS_CC_* above) and run
# under qemu-user, pinned hashes included: make test-aarch64, test-armhf (32-bit ARM, hard
# float), test-i386 (SSE2 arithmetic, FPMATH above; 32-bit pointers and sizes; a 64-bit
# kernel may not run 32-bit programs itself; an x87 build is refused first), test-s390x
# (big-endian).  tools/install-deps.sh --aarch64 / --armhf / --i386 / --s390x.
$(CROSS_TESTS): test-%:
	@echo "== the C tests on $* (under $(CROSS_RUN_$*)), $(REAL)"
	@$(MAKE) --no-print-directory B=$(B)/$*-tests REAL=$(REAL) CC="$(CROSS_CC_$*)" EXTRA_CFLAGS= \
	  TEST_RUN=$(CROSS_RUN_$*) check-c
test-i386: check-x87-refused
.PHONY: check-x87-refused
check-x87-refused:
	@printf '#include "vec2.h"\nint main(void) { return 0; }\n' | $(CROSS_CC_i386) -std=c99 $(REAL_FLAGS) \
	   -mfpmath=387 -Iinclude -Isrc -x c -o /dev/null - 2>&1 | grep -q 'excess floating-point precision' \
	 && echo "== an x87 build (-mfpmath=387) is refused" || { echo "an x87 build was not refused"; exit 1; }

check-ffi: $(LIB_SO)
	@echo "== tests/test_ffi.py"
	$(FFI_ENV) $(PYTHON) tests/test_ffi.py $(LIB_SO)

# The README's C examples (the block after each `<!-- example:c NAME -->` line), extracted,
# compiled and run, so they stay true.
README_C := main rollback threads slots
$(B)/readme/%.c: README.md
	@mkdir -p $(@D)
	awk -v name='$*' '$$0 == "<!-- example:c " name " -->" {on=1; next} on && /^```c/ {inb=1; next} inb && /^```/ {exit} inb {print}' $< > $@
	@test -s $@ || { echo "README.md has no C example '$*'"; exit 1; }

$(B)/readme/%: $(B)/readme/%.c $(LIB_A)
	$(CC) $(CFLAGS) $(TEST_CFLAGS) $(LDFLAGS) -o $@ $< $(LIB_A) $(LDLIBS)

check-readme: $(patsubst %,$(B)/readme/%,$(README_C))
	@for e in $(README_C); do echo "== README C example: $$e"; $(B)/readme/$$e || exit 1; done

# The shared library exports the API and nothing else.
check-exports: $(LIB_SO)
	@echo "== exports of $(LIB_SO)"
	@bad=$$(nm -D --defined-only $(LIB_SO) | awk '{print $$3}' | grep -v '^rg_' | grep -v '^_' || true); \
	 if [ -n "$$bad" ]; then echo "exported outside rg_*: $$bad"; exit 1; fi; \
	 echo "$$(nm -D --defined-only $(LIB_SO) | grep -c ' T rg_') rg_* functions, nothing else"

# No library module calls another that calls it back (from the symbols of librigid.a).
check-modules: $(LIB_A)
	@echo "== module layers of $(LIB_A)"
	@$(PYTHON) tools/check-modules.py $(LIB_A)

# Installs what is missing (tools/install-deps.sh is a no-op when all is there).
deps:
	@tools/install-deps.sh

test: deps
	@$(MAKE) --no-print-directory test-all

test-all: $(ALL_TARGETS)
	@fail=0; for r in $(TEST_RUNS); do $(MAKE) --no-print-directory $$r || fail=1; done; \
	 if [ $$fail -ne 0 ]; then echo "make test: FAILED"; exit 1; fi; echo "make test: all passed ($(REAL))"

# Both compilers' sanitizers (gcc's and clang's UBSan see different things): each builds in
# its own folder.  Python loads the sanitized library with the compiler's ASan runtime
# preloaded (gcc: libasan.so; clang: libclang_rt.asan-<arch>.so, which carries UBSan too).
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g
CC_IS_CLANG := $(findstring clang,$(shell $(CC) --version 2>/dev/null | head -n 1))
SAN_B := build/sanitize$(if $(CC_IS_CLANG),-clang)
SAN_RT := $(if $(CC_IS_CLANG),libclang_rt.asan-$(shell uname -m).so,libasan.so)
# clang links its runtime statically into executables only; linked as a shared library (as
# gcc's is) the sanitized librigid.so names it, so programs built against it link too.
comma := ,
SAN_LINK := $(if $(CC_IS_CLANG),-shared-libasan -Wl$(comma)-rpath$(comma)$(shell $(CC) -print-runtime-dir))
sanitize: deps
	@$(MAKE) --no-print-directory test-all B=$(SAN_B) OPT=-O1 $(if $(CC_IS_CLANG),$(SAN_KNOWN_VARS)) \
	  EXTRA_CFLAGS="$(SAN_FLAGS)" EXTRA_LDFLAGS="$(SAN_FLAGS) $(SAN_LINK)" \
	  FFI_ENV="LD_PRELOAD=$$($(CC) -print-file-name=$(SAN_RT)) ASAN_OPTIONS=detect_leaks=0"

# The threaded tests under ThreadSanitizer (clang's: gcc 12's runtime does not start on this
# kernel), with tests/tsan.supp: the one benign race it names, nothing else.
TSAN_B := build/tsan
tsan: deps
	@tools/install-deps.sh --fuzz
	@$(MAKE) --no-print-directory B=$(TSAN_B) CC=clang OPT=-O1 EXTRA_CFLAGS="-fsanitize=thread -g" \
	  EXTRA_LDFLAGS="-fsanitize=thread" $(TSAN_B)/tests/test_threads $(TSAN_B)/tests/test_restore_threads \
	  $(TSAN_B)/tests/test_bands
	@echo "== $(TSAN_B)/tests/test_threads under ThreadSanitizer"
	@TSAN_OPTIONS="suppressions=tests/tsan.supp halt_on_error=1" $(TSAN_B)/tests/test_threads
	@echo "== $(TSAN_B)/tests/test_restore_threads under ThreadSanitizer"
	@TSAN_OPTIONS="suppressions=tests/tsan.supp halt_on_error=1" $(TSAN_B)/tests/test_restore_threads
	@echo "== $(TSAN_B)/tests/test_bands under ThreadSanitizer"
	@TSAN_OPTIONS="suppressions=tests/tsan.supp halt_on_error=1" $(TSAN_B)/tests/test_bands

# The tests of random scenes, snapshots and contacts under valgrind's memcheck: a read of
# memory nothing wrote (which AddressSanitizer does not see) that decides a branch or a
# result fails them.  A step that read such memory replayed otherwise after a restore only
# now and then (12ecf4a, 6019e53); this finds it every time.
MEMCHECK_B := build/memcheck
MEMCHECK_TESTS := test_random_more test_rollback test_solver test_island test_determinism
memcheck: deps
	@tools/install-deps.sh --memcheck
	@$(MAKE) --no-print-directory B=$(MEMCHECK_B) OPT="-O2 -g" $(MEMCHECK_TESTS:%=$(MEMCHECK_B)/tests/%)
	@pass=0; fail=0; for t in $(MEMCHECK_TESTS); do echo "== $(MEMCHECK_B)/tests/$$t under valgrind"; \
	   if valgrind -q --error-exitcode=99 --track-origins=yes $(MEMCHECK_B)/tests/$$t > $(MEMCHECK_B)/$$t.log 2>&1; \
	   then pass=$$((pass + 1)); else fail=$$((fail + 1)); cat $(MEMCHECK_B)/$$t.log; fi; \
	 done; echo "$$pass passed, $$fail failed"; [ $$fail -eq 0 ]

# ---------------------------------------------------------------- install
# The header, the library (static, shared with its SONAME and links) and its pc file; the
# Lua parts come from lua/lua.mk.  The pc file is rebuilt whenever what it says changes
# (PREFIX among it): $(B)/pc.vars holds that and is rewritten only when it differs.
PC := $(B)/$(LIB_NAME).pc
PC_VARS := $(PREFIX) $(VERSION) $(LIB_NAME) $(REAL_FLAGS)
OTHER_LIB := $(if $(filter double,$(REAL)),rigid,rigid-double)
FORCE:
$(B)/pc.vars: FORCE
	@mkdir -p $(@D)
	@echo '$(PC_VARS)' | cmp -s - $@ || echo '$(PC_VARS)' > $@

$(PC): $(B)/pc.vars
	printf 'prefix=%s\nlibdir=$${prefix}/lib\nincludedir=$${prefix}/include\n\nName: %s\nDescription: 2D game physics in C99 (%s)\nVersion: %s\nCflags: -I$${includedir} %s\nLibs: -L$${libdir} -l%s\nLibs.private: -lm -pthread\n' \
	  '$(PREFIX)' '$(LIB_NAME)' '$(REAL)' '$(VERSION)' '$(REAL_FLAGS)' '$(LIB_NAME)' > $@

install: $(LIB_A) $(LIB_SO) $(PC)
	install -d $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 644 include/rigid.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 $(LIB_A) $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(LIB_SO) $(DESTDIR)$(PREFIX)/lib/lib$(LIB_NAME).so.$(VERSION)
	ln -sf lib$(LIB_NAME).so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(PREFIX)/lib/lib$(LIB_NAME).so
	install -m 644 $(PC) $(DESTDIR)$(PREFIX)/lib/pkgconfig/

# The header stays while the other build's library is installed.  The directories are
# the usual ones of a prefix (bin, include, lib...), which other packages share: they stay.
uninstall:
	rm -f $(addprefix $(DESTDIR)$(PREFIX)/lib/,lib$(LIB_NAME).a lib$(LIB_NAME).so.$(VERSION) \
	  $(SONAME) lib$(LIB_NAME).so pkgconfig/$(LIB_NAME).pc)
	[ -e $(DESTDIR)$(PREFIX)/lib/lib$(OTHER_LIB).so.$(VERSION) ] || rm -f $(DESTDIR)$(PREFIX)/include/rigid.h

# Install and uninstall into a temporary DESTDIR, programs built against the installed pc.
check-install: $(LIB_A) $(LIB_SO) $(ALL_TARGETS)
	@echo "== tests/test_install.sh ($(REAL))"
	@RUN_ENV="$(FFI_ENV)" tests/test_install.sh "$(MAKE)" $(REAL) $(B) "$(CC)"

clean:
	rm -rf build


-include $(LIB_OBJ:.o=.d) $(TEST_BINS:=.d)
