# make bench: what snapshots cost (tools/bench_snapshot.c).
BENCH_SNAPSHOT := $(B)/bench-snapshot
ALL_TARGETS += $(BENCH_SNAPSHOT)
.PHONY: bench-snapshot
bench: bench-snapshot

$(BENCH_SNAPSHOT): tools/bench_snapshot.c $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $< $(LIB_A) $(LDLIBS)

bench-snapshot: $(BENCH_SNAPSHOT)
	@echo "== snapshots: bytes, save, restore, hash"
	@$(BENCH_SNAPSHOT)
