# The library and its C tests built by tcc, a C99 compiler without GCC's extensions: every
# portable branch of src/ (no __builtin_*, no AVX2 paths, no ifunc dispatch, the solver's
# bands off for want of atomics, the process clock for a world's seed) is compiled and run,
# and the pinned hashes must hold for a third compiler.  thread_pool.c needs GCC's atomics:
# it comes from $(CC)'s build of this tree (the same calling convention).  Left out: the
# tests that use GCC's atomics themselves (test_bands, test_threads).  make test-tcc
# [REAL=double].
TCC ?= tcc
TCC_B := $(B)/tcc
TCC_SKIP := test_bands test_threads
TCC_TESTS := $(filter-out $(TCC_SKIP),$(patsubst tests/%.c,%,$(TEST_SRC)))
.PHONY: test-tcc
test-tcc: $(B)/obj/thread_pool.o
	@echo "== the library and the C tests built by tcc, $(REAL)"
	@if ! command -v $(TCC) >/dev/null 2>&1; then echo "  skipped: tcc is not installed"; exit 0; fi; \
	 mkdir -p $(TCC_B)/obj $(TCC_B)/tests; \
	 for f in $(filter-out src/thread_pool.c,$(LIB_SRC)); do \
	   $(TCC) -std=c99 -Werror $(REAL_FLAGS) -Iinclude -Isrc -c $$f -o $(TCC_B)/obj/$$(basename $$f .c).o \
	     || exit 1; \
	 done; \
	 rm -f $(TCC_B)/librigid.a; ar rcs $(TCC_B)/librigid.a $(TCC_B)/obj/*.o $(B)/obj/thread_pool.o; \
	 fail=0; for t in $(TCC_TESTS); do \
	   extra=; [ $$t = test_accuracy ] && extra="$(ACC_DEFS) $(ACC_SHARED)"; \
	   $(TCC) -std=c99 -Werror $(REAL_FLAGS) -Iinclude -Isrc -Itests -Itools -o $(TCC_B)/tests/$$t \
	     tests/$$t.c $$extra $(TCC_B)/librigid.a $(CMOCKA_LIBS) -lm -lpthread || { fail=1; continue; }; \
	   echo "== $(TCC_B)/tests/$$t"; $(TCC_B)/tests/$$t || fail=1; \
	 done; exit $$fail
