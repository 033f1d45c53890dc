# The benchmark: tools/bench.c and its parts (bench_run, bench_scenes, bench_quality,
# bench_report, bench_sweep, bench_floor) and engines (bench_rigid, bench_box2d, bench_chipmunk, bench_v3).
#   make bench                 installs the peers (tools/install-deps.sh --bench), builds Box2D v3
#                              (tools/bench_v3.mk) and runs every scene on rigid, Box2D v3, Box2D
#                              2.4 and Chipmunk 7 side by side (without those it cannot have, and
#                              says so); CSV in $(B)/charts/bench.csv
#   make bench BENCH_ARGS=--quick          a smoke run (any bench option goes in BENCH_ARGS)
#   make charts                also plots ms/step against N (log-log) into $(B)/charts/bench_scaling.*
#                              and quality against cost into $(B)/charts/bench_pareto.*
#
# $(B)/bench (rigid, and v3 when built) is part of `make`; Box2D 2.4 and Chipmunk are compiled
# only for `make bench`, with their own flags (their headers are not -Wpedantic -Werror
# clean), into $(B)/bench-peers.

# Scenes with shapes need the collision API: enabled as soon as the header declares it and
# src/ defines every function the bench calls (so a half-landed API never breaks `make`).
BENCH_COLLISION_FNS := rg_body_set_circle rg_body_set_aabb rg_body_set_friction \
                       rg_body_set_restitution rg_body_set_sensor rg_body_set_one_way \
                       rg_world_set_pre_solve rg_body_get_contacts rg_world_touching_count
BENCH_OPEN := (
BENCH_COLLISION_MISSING := $(foreach f,$(BENCH_COLLISION_FNS),\
  $(if $(shell grep -l '^RG_API[^;]*[ *]$(f)[$(BENCH_OPEN)]' src/*.c 2>/dev/null),,$(f)))
BENCH_COLLISION := $(strip $(if $(shell grep -l 'rg_body_set_circle' include/rigid.h 2>/dev/null),\
  $(if $(strip $(BENCH_COLLISION_MISSING)),,-DRG_BENCH_COLLISION)))
# The task system (rg_thread_pool_create) likewise: the bench's threaded rigid runs.
BENCH_THREADS := $(if $(shell grep -l 'rg_thread_pool_create' include/rigid.h 2>/dev/null),\
  $(if $(shell grep -l '^RG_API[^;]*[ *]rg_thread_pool_create[$(BENCH_OPEN)]' src/*.c 2>/dev/null),\
  -DRG_BENCH_THREADS))
BENCH_COLLISION_STAMP := $(B)/bench_obj/collision-$(if $(BENCH_COLLISION),on,off)-threads-$(if $(BENCH_THREADS),on,off)
BENCH_CFLAGS = $(CFLAGS) $(BENCH_COLLISION) $(BENCH_THREADS)
BENCH_CXX ?= g++
BENCH_PEER_LIBS := -lbox2d -lchipmunk
BENCH_LIBS := -ldl -lm
BENCH_ARGS ?=
BENCH_SWEEP_ARGS ?= --repeats 1
BENCH_CHART_ARGS ?= --repeats 1 --sleep off --engine rigid,rigid-$(BENCH_NPROC)w,b2v3-avx2,b2v3-avx2-$(BENCH_NPROC)w,box2d,chipmunk \
                    --scene rain:1000,2000,4000,10000,20000 --scene boxes:1000,2000,4000,10000,20000,100000 \
                    --scene free0:1000,10000,100000,1000000
BENCH_NPROC := $(shell nproc 2>/dev/null || echo 2)

ALL_TARGETS += $(B)/bench

# The parts every bench program shares, and those of the harness.
BENCH_COMMON := scenes rigid gameplay v3_load
BENCH_PARTS := $(BENCH_COMMON) run quality report sweep floor cores
BENCH_PART_OBJ := $(patsubst %,$(B)/bench_obj/bench_%.o,$(BENCH_PARTS))
BENCH_COMMON_OBJ := $(patsubst %,$(B)/bench_obj/bench_%.o,$(BENCH_COMMON))

$(B)/bench_obj/bench.o: tools/bench.c tools/bench.h tools/bench_run.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(B)/bench_obj/bench_%.o: tools/bench_%.c tools/bench.h tools/bench_run.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

# The stamp's name changes when collision turns on, which rebuilds the rigid engine.
$(BENCH_COLLISION_STAMP):
	@mkdir -p $(@D)
	@touch $@

$(B)/bench_obj/bench_rigid.o: tools/bench_rigid.c tools/bench.h include/rigid.h $(BENCH_COLLISION_STAMP)
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(B)/bench: $(B)/bench_obj/bench.o $(BENCH_PART_OBJ) $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $^ $(BENCH_LIBS)

# ---------------------------------------------------------------- with the peers
$(B)/bench_obj/bench_peers.o: tools/bench.c tools/bench.h tools/bench_run.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -DRG_BENCH_PEERS -c $< -o $@

$(B)/bench_obj/bench_box2d.o: tools/bench_box2d.cpp tools/bench.h
	@mkdir -p $(@D)
	$(BENCH_CXX) -std=c++20 -O2 -Itools -c $< -o $@

$(B)/bench_obj/bench_chipmunk.o: tools/bench_chipmunk.c tools/bench.h
	@mkdir -p $(@D)
	$(CC) -std=gnu99 -O2 -Itools -c $< -o $@

$(B)/bench-peers: $(B)/bench_obj/bench_peers.o $(BENCH_PART_OBJ) \
                  $(B)/bench_obj/bench_box2d.o $(B)/bench_obj/bench_chipmunk.o $(LIB_A)
	$(BENCH_CXX) $(LDFLAGS) -o $@ $^ $(BENCH_PEER_LIBS) $(BENCH_LIBS)

# The peers are there when their headers, libraries and a C++ compiler are.
BENCH_HAVE_PEERS = [ -f /usr/include/box2d/box2d.h ] && [ -f /usr/include/chipmunk/chipmunk.h ] && \
                   command -v $(BENCH_CXX) >/dev/null 2>&1

.PHONY: bench-main bench-deps charts-bench charts-bench-pareto
bench: bench-main
charts: charts-bench charts-bench-pareto

bench-deps:
	@tools/install-deps.sh --bench || echo "bench: could not install the peers; rigid runs alone"

# The shell that readies a harness: v3 (its directory, or none, from bench-v3), then the peer
# harness when it builds, else rigid's.
BENCH_READY = v3=$$($(MAKE) --no-print-directory bench-v3 | tail -n 1); \
  if $(BENCH_HAVE_PEERS) && $(MAKE) --no-print-directory $(B)/bench-peers; then \
    exe=$(B)/bench-peers; \
  else \
    echo "bench: Box2D 2.4 and Chipmunk unavailable (libbox2d-dev, libchipmunk-dev, g++): without them"; \
    $(MAKE) --no-print-directory $(B)/bench || exit 1; exe=$(B)/bench; \
  fi

bench-main: bench-deps
	@mkdir -p $(B)/charts
	@$(BENCH_READY); \
	 echo "== $$exe --v3 $$v3 $(BENCH_ARGS) --csv $(B)/charts/bench.csv"; \
	 $$exe --v3 $$v3 $(BENCH_ARGS) --csv $(B)/charts/bench.csv

# Scaling chart: ms per step against N (log-log), every engine, sleeping off.
charts-bench: bench-deps
	@tools/install-deps.sh --charts || echo "charts: could not install gnuplot"
	@mkdir -p $(B)/charts
	@$(BENCH_READY); \
	 echo "== $$exe --v3 $$v3 $(BENCH_CHART_ARGS) --csv $(B)/charts/bench_scaling.csv"; \
	 $$exe --v3 $$v3 $(BENCH_CHART_ARGS) --csv $(B)/charts/bench_scaling.csv >$(B)/charts/bench_scaling.txt \
	   || exit 1; \
	 cat $(B)/charts/bench_scaling.txt
	gnuplot -e "csv='$(B)/charts/bench_scaling.csv'; out='$(B)/charts/bench_scaling'" tools/bench.gp
	@echo "charts: $(B)/charts/bench_scaling.svg $(B)/charts/bench_scaling.png" \
	      "(the README's copy: tools/charts/bench_scaling.*)"

# Quality against cost: every engine at several solver settings (bench --sweep), the Pareto chart.
charts-bench-pareto: bench-deps
	@tools/install-deps.sh --charts || echo "charts: could not install gnuplot"
	@mkdir -p $(B)/charts
	@$(BENCH_READY); \
	 echo "== $$exe --v3 $$v3 --sweep $(BENCH_SWEEP_ARGS) --csv $(B)/charts/bench_pareto.csv"; \
	 $$exe --v3 $$v3 --sweep $(BENCH_SWEEP_ARGS) --csv $(B)/charts/bench_pareto.csv \
	   >$(B)/charts/bench_pareto.txt || exit 1; \
	 cat $(B)/charts/bench_pareto.txt
	gnuplot -e "csv='$(B)/charts/bench_pareto.csv'; out='$(B)/charts/bench_pareto'" tools/charts/bench_pareto.gp
	@echo "charts: $(B)/charts/bench_pareto.svg $(B)/charts/bench_pareto.png" \
	      "(the README's copy: tools/charts/bench_pareto.*)"

-include $(patsubst %.o,%.d,$(B)/bench_obj/bench.o $(B)/bench_obj/bench_peers.o $(BENCH_PART_OBJ) \
                               $(B)/bench_obj/bench_snapshot.o)
