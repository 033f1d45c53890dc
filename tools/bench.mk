# The benchmark: tools/bench.c and its engines.
#   make bench                 installs the peers (tools/install-deps.sh --bench) and runs every
#                              scene on rigid, Box2D 2.4 and Chipmunk 7 side by side (rigid alone
#                              when the peers cannot be installed); CSV in $(B)/charts/bench.csv
#   make bench BENCH_ARGS=--quick          a smoke run (any bench option goes in BENCH_ARGS)
#   make charts                also plots ms/step against N (log-log) into $(B)/charts/bench_scaling.*
#
# $(B)/bench (rigid alone) is part of `make`; the peers are compiled only for `make bench`,
# with their own flags (their headers are not -Wpedantic -Werror clean), into $(B)/bench-peers.

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
BENCH_COLLISION_STAMP := $(B)/bench_obj/collision-$(if $(BENCH_COLLISION),on,off)
BENCH_CFLAGS = $(CFLAGS) $(BENCH_COLLISION)
BENCH_CXX ?= g++
BENCH_PEER_LIBS := -lbox2d -lchipmunk
BENCH_ARGS ?=
BENCH_CHART_ARGS ?= --repeats 1 --scene rain:500,1000,2000,4000,10000,20000 \
                    --scene boxes:500,1000,2000,4000,10000,20000 --scene free0:1000,10000,100000,1000000

ALL_TARGETS += $(B)/bench

$(B)/bench_obj/bench.o: tools/bench.c tools/bench.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

# The stamp's name changes when collision turns on, which rebuilds the rigid engine.
$(BENCH_COLLISION_STAMP):
	@mkdir -p $(@D)
	@touch $@

$(B)/bench_obj/bench_rigid.o: tools/bench_rigid.c tools/bench.h include/rigid.h $(BENCH_COLLISION_STAMP)
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(B)/bench_obj/bench_gameplay.o: tools/bench_gameplay.c tools/bench.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(B)/bench: $(B)/bench_obj/bench.o $(B)/bench_obj/bench_rigid.o $(B)/bench_obj/bench_gameplay.o $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

# ---------------------------------------------------------------- with the peers
$(B)/bench_obj/bench_peers.o: tools/bench.c tools/bench.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -DRG_BENCH_PEERS -c $< -o $@

$(B)/bench_obj/bench_box2d.o: tools/bench_box2d.cpp tools/bench.h
	@mkdir -p $(@D)
	$(BENCH_CXX) -std=c++17 -O2 -Itools -c $< -o $@

$(B)/bench_obj/bench_chipmunk.o: tools/bench_chipmunk.c tools/bench.h
	@mkdir -p $(@D)
	$(CC) -std=gnu99 -O2 -Itools -c $< -o $@

$(B)/bench-peers: $(B)/bench_obj/bench_peers.o $(B)/bench_obj/bench_rigid.o $(B)/bench_obj/bench_gameplay.o \
                  $(B)/bench_obj/bench_box2d.o $(B)/bench_obj/bench_chipmunk.o $(LIB_A)
	$(BENCH_CXX) $(LDFLAGS) -o $@ $^ $(BENCH_PEER_LIBS) $(LDLIBS)

# The peers are there when their headers, libraries and a C++ compiler are.
BENCH_HAVE_PEERS = [ -f /usr/include/box2d/box2d.h ] && [ -f /usr/include/chipmunk/chipmunk.h ] && \
                   command -v $(BENCH_CXX) >/dev/null 2>&1

.PHONY: bench-main bench-deps charts-bench
bench: bench-main
charts: charts-bench

bench-deps:
	@tools/install-deps.sh --bench || echo "bench: could not install the peers; rigid runs alone"

# Builds the peer harness when it can, else rigid's; prints which one ran.
bench-main: bench-deps
	@mkdir -p $(B)/charts
	@if $(BENCH_HAVE_PEERS) && $(MAKE) --no-print-directory $(B)/bench-peers; then \
	   exe=$(B)/bench-peers; \
	 else \
	   echo "bench: peers unavailable (libbox2d-dev, libchipmunk-dev, g++): rigid alone"; \
	   $(MAKE) --no-print-directory $(B)/bench || exit 1; exe=$(B)/bench; \
	 fi; \
	 echo "== $$exe $(BENCH_ARGS) --csv $(B)/charts/bench.csv"; \
	 $$exe $(BENCH_ARGS) --csv $(B)/charts/bench.csv

# Scaling chart: ms per step against N (log-log), rigid and the peers.
charts-bench: bench-deps
	@tools/install-deps.sh --charts || echo "charts: could not install gnuplot"
	@mkdir -p $(B)/charts
	@if $(BENCH_HAVE_PEERS) && $(MAKE) --no-print-directory $(B)/bench-peers; then \
	   exe=$(B)/bench-peers; \
	 else \
	   $(MAKE) --no-print-directory $(B)/bench || exit 1; exe=$(B)/bench; \
	 fi; \
	 echo "== $$exe $(BENCH_CHART_ARGS) --csv $(B)/charts/bench_scaling.csv"; \
	 $$exe $(BENCH_CHART_ARGS) --csv $(B)/charts/bench_scaling.csv >$(B)/charts/bench_scaling.txt \
	   || exit 1; \
	 cat $(B)/charts/bench_scaling.txt
	gnuplot -e "csv='$(B)/charts/bench_scaling.csv'; out='$(B)/charts/bench_scaling'" tools/bench.gp
	@echo "charts: $(B)/charts/bench_scaling.svg $(B)/charts/bench_scaling.png" \
	      "(the README's copy: tools/charts/bench_scaling.*)"

-include $(B)/bench_obj/bench.d $(B)/bench_obj/bench_rigid.d $(B)/bench_obj/bench_peers.d \
         $(B)/bench_obj/bench_gameplay.d
