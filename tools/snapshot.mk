# Snapshots across builds and machines (tools/snaptool.c): the state hash of one scene from
# the default build, -O0, -O3, clang and the SSE2-only build (no AVX2 dispatch) must agree,
# and a snapshot saved on x86-64 must continue on aarch64, 32-bit ARM, 32-bit x86 and s390x
# (big-endian), under qemu-user, to the same hash and back (CROSS_MACHINES, Makefile).  The
# variants build into $(B)/hv-*/, the other machines' into $(B)/<machine>/.
SNAPTOOL := $(B)/snaptool
ALL_TARGETS += $(SNAPTOOL)
TEST_RUNS += check-hash-variants check-cross-machine
.PHONY: check-hash-variants check-cross-machine

$(SNAPTOOL): tools/snaptool.c $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $< $(LIB_A) $(LDLIBS)

# name:make arguments (no sanitizers: those are the run this may be part of)
HASH_VARIANTS := O0:OPT=-O0 O3:OPT=-O3 sse2:EXTRA_CFLAGS=-DRG_NO_DISPATCH clang:CC=clang
check-hash-variants: $(SNAPTOOL)
	@echo "== the state hash in every build ($(REAL))"
	@ref=$$($(SNAPTOOL) hash) || exit 1; echo "  this build ($(CC) $(OPT) $(EXTRA_CFLAGS)) $$ref"; fail=0; \
	 for v in $(HASH_VARIANTS); do name=$${v%%:*}; args=$${v#*:}; \
	   if [ "$$name" = clang ] && ! command -v clang >/dev/null 2>&1; then echo "  clang: not installed, skipped"; continue; fi; \
	   $(MAKE) --no-print-directory -s B=$(B)/hv-$$name REAL=$(REAL) EXTRA_CFLAGS= EXTRA_LDFLAGS= $$args \
	     $(B)/hv-$$name/snaptool >/dev/null || { echo "  $$name: build failed"; fail=1; continue; }; \
	   h=$$($(B)/hv-$$name/snaptool hash); \
	   if [ "$$h" = "$$ref" ]; then echo "  $$name $$h"; else echo "  $$name $$h DIFFERS"; fail=1; fi; \
	 done; \
	 if [ $$fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi; exit $$fail

# each machine as name,compiler,emulator (a compiler's spaces written @ inside the list)
SNAP_EMPTY :=
SNAP_SPACE := $(SNAP_EMPTY) $(SNAP_EMPTY)
SNAP_MACHINES := $(foreach m,$(CROSS_MACHINES),$(m),$(subst $(SNAP_SPACE),@,$(strip $(CROSS_CC_$(m)))),$(CROSS_RUN_$(m)))
check-cross-machine: $(SNAPTOOL)
	@echo "== snapshots across machines: x86-64 and $(CROSS_MACHINES) (qemu-user), $(REAL)"
	@fail=0; ran=0; for m in $(SNAP_MACHINES); do \
	   name=$${m%%,*}; rest=$${m#*,}; cc=$$(echo "$${rest%%,*}" | tr '@' ' '); emu=$${rest#*,}; \
	   if ! command -v $${cc%% *} >/dev/null 2>&1 || ! command -v $$emu >/dev/null 2>&1 || \
	      ! echo 'int main(void){return 0;}' | $$cc -static -x c -o /dev/null - 2>/dev/null; then \
	     echo "  $$name: skipped, $$cc or $$emu cannot build or run (tools/install-deps.sh --cross)"; continue; fi; \
	   $(MAKE) --no-print-directory -s B=$(B)/$$name REAL=$(REAL) CC="$$cc" EXTRA_CFLAGS= \
	     EXTRA_LDFLAGS=-static $(B)/$$name/snaptool >/dev/null || { echo "  $$name: build failed"; fail=1; continue; }; \
	   other="$$emu $(B)/$$name/snaptool"; ran=$$((ran + 1)); \
	   h1=$$($(SNAPTOOL) hash); h2=$$($$other hash); \
	   [ "$$h1" = "$$h2" ] || { echo "  the same scene: x86-64 $$h1, $$name $$h2"; fail=1; }; \
	   s1=$$($(SNAPTOOL) save $(B)/snap-x86.bin); r1=$$($$other restore $(B)/snap-x86.bin); \
	   [ "$$s1" = "$$r1" ] || { echo "  saved on x86-64, continued on $$name: $$s1 / $$r1"; fail=1; }; \
	   s2=$$($$other save $(B)/snap-$$name.bin); r2=$$($(SNAPTOOL) restore $(B)/snap-$$name.bin); \
	   [ "$$s2" = "$$r2" ] || { echo "  saved on $$name, continued on x86-64: $$s2 / $$r2"; fail=1; }; \
	   echo "  $$name: hash $$h2, saved and continued both ways: $$s1 $$r1 $$s2 $$r2"; \
	 done; \
	 if [ $$fail -eq 0 ]; then echo "$$ran passed, 0 failed"; else echo "0 passed, 1 failed"; fi; exit $$fail
