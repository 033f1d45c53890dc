# Which of a step's tasks a second worker pays for on this machine (tools/bench_tasks.c):
# make bench-tasks [TASKS_ARGS="SCENE:N ... --steps S"] (defaults boxes:10000 rain:10000,
# 400 steps; some minutes at 10,000 bodies: three worlds step in turns once per task).
BENCH_TASKS := $(B)/bench-tasks
ALL_TARGETS += $(BENCH_TASKS)
.PHONY: bench-tasks
$(B)/bench_obj/bench_tasks.o: tools/bench_tasks.c tools/bench.h tools/bench_run.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(BENCH_TASKS): $(B)/bench_obj/bench_tasks.o $(B)/bench_obj/bench_cores.o $(BENCH_COMMON_OBJ) $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $^ $(BENCH_LIBS)

bench-tasks: $(BENCH_TASKS)
	$(BENCH_TASKS) $(TASKS_ARGS)

# Two builds' threaded steps side by side (tools/bench_ab_threads.c): make bench-ab-threads
# AB_A=old.so AB_B=new.so [AB_ARGS="SCENE N STEPS"].
BENCH_AB_THREADS := $(B)/bench-ab-threads
ALL_TARGETS += $(BENCH_AB_THREADS)
.PHONY: bench-ab-threads
$(B)/bench_obj/bench_ab_threads.o: tools/bench_ab_threads.c tools/bench.h tools/bench_run.h
	@mkdir -p $(@D)
	$(CC) $(BENCH_CFLAGS) -c $< -o $@

$(BENCH_AB_THREADS): $(B)/bench_obj/bench_ab_threads.o $(B)/bench_obj/bench_cores.o $(BENCH_COMMON_OBJ) $(LIB_A)
	$(CC) $(LDFLAGS) -o $@ $^ $(BENCH_LIBS)

bench-ab-threads: $(BENCH_AB_THREADS)
	@test -n "$(AB_A)" -a -n "$(AB_B)" || { echo "make bench-ab-threads AB_A=a.so AB_B=b.so [AB_ARGS=\"SCENE N STEPS\"]"; exit 2; }
	$(BENCH_AB_THREADS) $(AB_A) $(AB_B) $(AB_ARGS)
