# make bench: what snapshots cost (tools/bench_snapshot.c), rigid and Box2D v3 side by side.
BENCH_SNAPSHOT := $(B)/bench-snapshot
ALL_TARGETS += $(BENCH_SNAPSHOT)
.PHONY: bench-snapshot
bench: bench-snapshot

$(B)/bench_obj/bench_snapshot.o: tools/bench_snapshot.c tools/bench.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(BENCH_SNAPSHOT): $(B)/bench_obj/bench_snapshot.o $(BENCH_COMMON_OBJ) $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $^ $(BENCH_LIBS)

# After bench-main when both run (v3 is built by then; it builds it too when run alone);
# rain 1000 alone when BENCH_ARGS has --quick.
BENCH_SNAPSHOT_SIZES = $(if $(filter --quick,$(BENCH_ARGS)),1000)
bench-snapshot: $(BENCH_SNAPSHOT) $(if $(filter bench,$(MAKECMDGOALS)),bench-main)
	@v3=$$($(MAKE) --no-print-directory bench-v3 | tail -n 1); \
	 echo "== snapshots: bytes, save, restore, hash ($(BENCH_SNAPSHOT) --v3 $$v3 $(BENCH_SNAPSHOT_SIZES))"; \
	 $(BENCH_SNAPSHOT) --v3 $$v3 $(BENCH_SNAPSHOT_SIZES)

# Two builds' restores side by side (tools/bench_ab.c): make bench-ab AB_A=old.so AB_B=new.so
# [AB_ARGS="N STEPS PAIRS"], the .so files from make build/librigid.so in two trees.
BENCH_AB := $(B)/bench-ab
ALL_TARGETS += $(BENCH_AB)
.PHONY: bench-ab
$(B)/bench_obj/bench_ab.o: tools/bench_ab.c tools/bench.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(BENCH_AB): $(B)/bench_obj/bench_ab.o $(BENCH_COMMON_OBJ) $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $^ $(BENCH_LIBS)

bench-ab: $(BENCH_AB)
	@test -n "$(AB_A)" -a -n "$(AB_B)" || { echo "make bench-ab AB_A=a.so AB_B=b.so [AB_ARGS=\"N STEPS PAIRS\"]"; exit 2; }
	$(BENCH_AB) $(AB_A) $(AB_B) $(AB_ARGS)
