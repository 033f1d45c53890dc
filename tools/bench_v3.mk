# Box2D v3 in the bench (tools/bench_v3.c), built from its source at BOX2D_V3_DIR: by default
# ../shared/peers/box2d-v3 (from the repository's root; see its PEER.md), or a checkout of
# your own with `make bench BOX2D_V3_DIR=path`.  Never copied into the repository.
#   make bench-v3     v3's src/*.c compiled twice with plain compiler calls, in its default
#                     SSE2 build and its AVX2 build (-DBOX2D_AVX2 -mavx2 -mfma), each linked
#                     with tools/bench_v3.c into a shared library that hides every v3 symbol
#                     but the engine ($(B)/bench-v3/libbench-v3-{sse2,avx2}.so), which the bench
#                     opens at run time.  Says so and builds nothing when the source is absent.
# Only `make bench` and `make charts` build it: not `make`, not `make test`.
BOX2D_V3_DIR ?= ../shared/peers/box2d-v3
BENCH_V3_B := $(B)/bench-v3
BENCH_V3_SRC := $(wildcard $(BOX2D_V3_DIR)/src/*.c)
BENCH_V3_HAVE := $(if $(wildcard $(BOX2D_V3_DIR)/include/box2d/box2d.h),$(if $(BENCH_V3_SRC),1))
BENCH_V3_CFLAGS := -std=c17 -O2 -DNDEBUG -ffp-contract=off -fPIC -fvisibility=hidden \
                   -I$(BOX2D_V3_DIR)/include -I$(BOX2D_V3_DIR)/src
BENCH_V3_SIMD_sse2 :=
BENCH_V3_SIMD_avx2 := -DBOX2D_AVX2 -mavx2 -mfma
BENCH_V3_LIBS := $(BENCH_V3_B)/libbench-v3-sse2.so $(BENCH_V3_B)/libbench-v3-avx2.so

bench_v3_objs = $(patsubst $(BOX2D_V3_DIR)/src/%.c,$(BENCH_V3_B)/$(1)/%.o,$(BENCH_V3_SRC))

# The source directory's path: a build from another checkout rebuilds every object.
$(BENCH_V3_B)/source: FORCE
	@mkdir -p $(@D)
	@echo '$(abspath $(BOX2D_V3_DIR))' | cmp -s - $@ || echo '$(abspath $(BOX2D_V3_DIR))' > $@

define BENCH_V3_BUILD
$(BENCH_V3_B)/$(1)/%.o: $(BOX2D_V3_DIR)/src/%.c $(BENCH_V3_B)/source
	@mkdir -p $$(@D)
	$$(CC) $(BENCH_V3_CFLAGS) $(BENCH_V3_SIMD_$(1)) -MMD -MP -c $$< -o $$@

$(BENCH_V3_B)/libbench-v3-$(1).so: tools/bench_v3.c tools/bench.h $(call bench_v3_objs,$(1))
	$$(CC) $(BENCH_V3_CFLAGS) $(BENCH_V3_SIMD_$(1)) -DBENCH_V3_SOURCE='"$(abspath $(BOX2D_V3_DIR))"' \
	  -shared -o $$@ $$< $(call bench_v3_objs,$(1)) -lm -lpthread

-include $(patsubst %.o,%.d,$(call bench_v3_objs,$(1)))
endef
$(foreach b,sse2 avx2,$(eval $(call BENCH_V3_BUILD,$(b))))

# Prints the bench's --v3 argument last: the directory, or none (and why) when v3 is absent
# or does not build.
.PHONY: bench-v3
bench-v3:
	@if [ -z "$(BENCH_V3_HAVE)" ]; then \
	   echo "bench: Box2D v3 not found at $(BOX2D_V3_DIR) (make bench BOX2D_V3_DIR=path): the rest runs without it" >&2; \
	   echo none; \
	 elif $(MAKE) --no-print-directory $(BENCH_V3_LIBS) >&2; then \
	   echo $(BENCH_V3_B); \
	 else \
	   echo "bench: Box2D v3 did not build from $(BOX2D_V3_DIR): the rest runs without it" >&2; \
	   echo none; \
	 fi
