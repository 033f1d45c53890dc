# Snapshots across builds and machines (tools/snaptool.c): the state hash of one scene from
# the default build, -O0, -O3, clang and the SSE2-only build (no AVX2 dispatch) must agree,
# and a snapshot saved on x86-64 must continue on aarch64 (qemu-user) to the same hash and
# back.  The variants build into $(B)/hv-*/, the aarch64 one into $(B)/aarch64/.
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

AARCH64_CC ?= aarch64-linux-gnu-gcc
QEMU_AARCH64 ?= qemu-aarch64
check-cross-machine: $(SNAPTOOL)
	@echo "== snapshots across machines: x86-64 and aarch64 (qemu-user), $(REAL)"
	@if ! command -v $(AARCH64_CC) >/dev/null 2>&1 || ! command -v $(QEMU_AARCH64) >/dev/null 2>&1; then \
	   echo "  skipped: $(AARCH64_CC) or $(QEMU_AARCH64) is not installed (tools/install-deps.sh --cross)"; exit 0; fi; \
	 $(MAKE) --no-print-directory -s B=$(B)/aarch64 REAL=$(REAL) CC=$(AARCH64_CC) EXTRA_CFLAGS= \
	   EXTRA_LDFLAGS=-static $(B)/aarch64/snaptool >/dev/null || exit 1; \
	 arm="$(QEMU_AARCH64) $(B)/aarch64/snaptool"; fail=0; \
	 h1=$$($(SNAPTOOL) hash); h2=$$($$arm hash); \
	 [ "$$h1" = "$$h2" ] || { echo "  the same scene: x86-64 $$h1, aarch64 $$h2"; fail=1; }; \
	 s1=$$($(SNAPTOOL) save $(B)/snap-x86.bin); r1=$$($$arm restore $(B)/snap-x86.bin); \
	 [ "$$s1" = "$$r1" ] || { echo "  saved on x86-64, continued on aarch64: $$s1 / $$r1"; fail=1; }; \
	 s2=$$($$arm save $(B)/snap-arm.bin); r2=$$($(SNAPTOOL) restore $(B)/snap-arm.bin); \
	 [ "$$s2" = "$$r2" ] || { echo "  saved on aarch64, continued on x86-64: $$s2 / $$r2"; fail=1; }; \
	 echo "  hash $$h1, saved and continued both ways: $$s1 $$r1 $$s2 $$r2"; \
	 if [ $$fail -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; fi; exit $$fail
