/* bench_cores.c: what moving data between two cores costs on this machine, for the bench's
 * machine line.  Two threads hand a counter back and forth, each waiting (spinning) for the
 * other's write: one round trip is a cache line gone to the other core and back.  And the
 * main thread reads, in a random order (independent loads, as a stage's reads of bodies
 * through its pairs), 8192 lines the other thread has just written, then the same lines
 * after writing them itself; and writes them, in order and in that random order, after the
 * other thread has only read them (its copies must go before each write: a stage that
 * rewrites what the other worker's stage only read pays that).  And both threads add to a
 * counter in memory at once, each timing its own: on a VM one of two virtual cpus may for
 * seconds run at a fraction of the other's speed, which bounds what a second worker can add
 * whatever the data's moves cost.  A step spread over workers moves its data between cores
 * stage after stage, so what a second worker gains depends on these (README, Known limits).
 * Where the two threads cannot run at once (one cpu, or under valgrind, which runs one
 * thread at a time and would take hours over the spins) the hand-overs stop at a deadline
 * and nothing is reported. */
#undef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "bench_run.h"

#define CORES_TRIPS 20000
#define CORES_RUNS 5
#define CORES_DEADLINE_S 0.2 /* a run; some 10 ms where the threads run at once */

static uint64_t cores_counter; /* odd: the main thread's turn is over; even: the other's */
static int cores_stop;         /* the main thread gave up: the other thread returns */

static double cores_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* The other thread's wait for the counter to reach v: 0 when the main thread gave up. */
static int cores_other_waits(uint64_t v)
{
    while (__atomic_load_n(&cores_counter, __ATOMIC_ACQUIRE) != v)
        if (__atomic_load_n(&cores_stop, __ATOMIC_RELAXED)) return 0;
    return 1;
}

/* The main thread's wait for the counter to reach v: 0 past the deadline from t0. */
static int cores_main_waits(uint64_t v, double t0)
{
    for (uint32_t spins = 1; __atomic_load_n(&cores_counter, __ATOMIC_ACQUIRE) != v; spins++)
        if (spins % 4096 == 0 && cores_now() - t0 > CORES_DEADLINE_S) return 0;
    return 1;
}

/* Starts fn as the other thread, the counter at 0; 0 when it cannot. */
static int cores_start(pthread_t *other, void *(*fn)(void *))
{
    __atomic_store_n(&cores_counter, 0, __ATOMIC_RELEASE);
    __atomic_store_n(&cores_stop, 0, __ATOMIC_RELEASE);
    return pthread_create(other, NULL, fn, NULL) == 0;
}

/* Stops the other thread (past a deadline, it returns from its wait) and joins it. */
static void cores_join(pthread_t other)
{
    __atomic_store_n(&cores_stop, 1, __ATOMIC_RELEASE);
    pthread_join(other, NULL);
}

static void *cores_other(void *arg)
{
    (void)arg;
    for (uint64_t i = 0; i < CORES_TRIPS; i++) {
        if (!cores_other_waits(2 * i + 1)) return NULL;
        __atomic_store_n(&cores_counter, 2 * i + 2, __ATOMIC_RELEASE);
    }
    return NULL;
}

/* One run's time a round trip, s; -1 past the deadline. */
static double cores_run(void)
{
    pthread_t other;
    if (!cores_start(&other, cores_other)) return -1;
    double t0 = cores_now(), t = -1;
    uint64_t i = 0;
    for (; i < CORES_TRIPS; i++) {
        __atomic_store_n(&cores_counter, 2 * i + 1, __ATOMIC_RELEASE);
        if (!cores_main_waits(2 * i + 2, t0)) break;
    }
    if (i == CORES_TRIPS) t = (cores_now() - t0) / CORES_TRIPS;
    cores_join(other);
    return t;
}

/* ---------------------------------------------------------------- lines another core wrote */

#define CORES_LINES 8192 /* 512 KB: within a core's own cache */

typedef struct cores_line {
    uint64_t v[8];
} cores_line;

/* What a run of the lines times (cores_lines_run). */
#define CORES_KINDS 4

static cores_line *cores_lines;
static uint32_t *cores_order; /* a random order of the lines */
static volatile uint64_t cores_sink;

static void cores_write(uint64_t base)
{
    for (uint32_t i = 0; i < CORES_LINES; i++) cores_lines[i].v[0] = base + i;
}

/* The time a line of reading the lines in cores_order, s. */
static double cores_read(void)
{
    double t0 = cores_now();
    uint64_t sum = 0;
    for (uint32_t i = 0; i < CORES_LINES; i++) sum += cores_lines[cores_order[i]].v[0];
    double t = (cores_now() - t0) / CORES_LINES;
    cores_sink = sum;
    return t;
}

/* The time a line of writing the lines in order, or in cores_order (shuffled), s. */
static double cores_write_timed(uint64_t base, int shuffled)
{
    double t0 = cores_now();
    if (shuffled)
        for (uint32_t i = 0; i < CORES_LINES; i++) cores_lines[cores_order[i]].v[0] = base + i;
    else
        cores_write(base);
    return (cores_now() - t0) / CORES_LINES;
}

static void *cores_writer(void *arg)
{
    (void)arg;
    if (!cores_other_waits(1)) return NULL;
    cores_write(1000);
    __atomic_store_n(&cores_counter, 2, __ATOMIC_RELEASE);
    return NULL;
}

static void *cores_reader(void *arg)
{
    (void)arg;
    if (!cores_other_waits(1)) return NULL;
    uint64_t sum = 0;
    for (uint32_t i = 0; i < CORES_LINES; i++) sum += cores_lines[i].v[0];
    cores_sink = sum;
    __atomic_store_n(&cores_counter, 2, __ATOMIC_RELEASE);
    return NULL;
}

/* Starts the other thread on fn and waits for it; 0 past the deadline. */
static int cores_other_runs(void *(*fn)(void *))
{
    pthread_t other;
    if (!cores_start(&other, fn)) return 0;
    double t0 = cores_now();
    __atomic_store_n(&cores_counter, 1, __ATOMIC_RELEASE);
    int ok = cores_main_waits(2, t0);
    cores_join(other);
    return ok;
}

/* One run: the time a line of reading lines the other thread wrote (t[0]) and lines this
 * thread wrote (t[1]), and of writing, in order (t[2]) and shuffled (t[3]), lines this thread
 * wrote and the other then read, s; 0 past the deadline. */
static int cores_lines_run(double t[CORES_KINDS])
{
    cores_write(0); /* both threads' caches start from the same state: lines this thread wrote */
    if (!cores_other_runs(cores_writer)) return 0;
    t[0] = cores_read();
    cores_write(2000);
    t[1] = cores_read();
    for (int shuffled = 0; shuffled < 2; shuffled++) {
        if (!cores_other_runs(cores_reader)) return 0;
        t[2 + shuffled] = cores_write_timed(3000, shuffled);
    }
    return 1;
}

static int cores_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_cores_round_trip_ns(void)
{
    if (sysconf(_SC_NPROCESSORS_ONLN) < 2) return -1;
    double t[CORES_RUNS];
    for (int r = 0; r < CORES_RUNS; r++)
        if ((t[r] = cores_run()) < 0) return -1;
    qsort(t, CORES_RUNS, sizeof t[0], cores_cmp);
    return t[CORES_RUNS / 2] * 1e9;
}

/* ---------------------------------------------------------------- each thread's own speed */

/* Additions to a counter in memory: on a core of its own some one a cycle (the load meets
 * the store before it in the core's pipeline), 4 ms a run; a core whose execution units
 * another thread shares (a VM's virtual cpu beside another's on one core) runs it slower, as
 * it runs a step's loads and stores. */
#define CORES_CHAIN 12000000

static double cores_chain_s; /* the other thread's time */

static double cores_chain(void)
{
    volatile uint64_t cell = 0;
    double t0 = cores_now();
    for (uint32_t i = 0; i < CORES_CHAIN; i++) cell += i;
    double t = cores_now() - t0;
    cores_sink = cell;
    return t;
}

static void *cores_chainer(void *arg)
{
    (void)arg;
    if (!cores_other_waits(1)) return NULL;
    cores_chain_s = cores_chain();
    __atomic_store_n(&cores_counter, 2, __ATOMIC_RELEASE);
    return NULL;
}

int bench_cores_speeds_ns(double *fast, double *slow)
{
    if (sysconf(_SC_NPROCESSORS_ONLN) < 2) return 0;
    double t[2][CORES_RUNS];
    for (int r = 0; r < CORES_RUNS; r++) {
        pthread_t other;
        if (!cores_start(&other, cores_chainer)) return 0;
        double t0 = cores_now();
        __atomic_store_n(&cores_counter, 1, __ATOMIC_RELEASE);
        double mine = cores_chain();
        /* the other thread's chain: given up 0.1 s after the start (a run takes some 4 ms) */
        int ok = cores_main_waits(2, t0 + 0.1);
        cores_join(other);
        if (!ok) return 0;
        t[0][r] = mine < cores_chain_s ? mine : cores_chain_s;
        t[1][r] = mine < cores_chain_s ? cores_chain_s : mine;
    }
    qsort(t[0], CORES_RUNS, sizeof t[0][0], cores_cmp);
    qsort(t[1], CORES_RUNS, sizeof t[1][0], cores_cmp);
    *fast = t[0][CORES_RUNS / 2] / CORES_CHAIN * 1e9;
    *slow = t[1][CORES_RUNS / 2] / CORES_CHAIN * 1e9;
    return 1;
}

int bench_cores_lines_ns(double *other, double *own, double *shared, double *shared_shuffled)
{
    if (sysconf(_SC_NPROCESSORS_ONLN) < 2) return 0;
    cores_lines = malloc(CORES_LINES * sizeof *cores_lines);
    cores_order = malloc(CORES_LINES * sizeof *cores_order);
    int ok = cores_lines != NULL && cores_order != NULL;
    double t[CORES_KINDS][CORES_RUNS];
    if (ok) {
        uint32_t x = 2463534242u; /* xorshift: a fixed shuffle */
        for (uint32_t i = 0; i < CORES_LINES; i++) cores_order[i] = i;
        for (uint32_t i = CORES_LINES - 1; i > 0; i--) {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            uint32_t j = x % (i + 1), k = cores_order[i];
            cores_order[i] = cores_order[j];
            cores_order[j] = k;
        }
        for (int r = 0; r < CORES_RUNS && ok; r++) {
            double tr[CORES_KINDS];
            ok = cores_lines_run(tr);
            for (int u = 0; u < CORES_KINDS; u++) t[u][r] = tr[u];
        }
    }
    if (ok) {
        for (int u = 0; u < CORES_KINDS; u++) qsort(t[u], CORES_RUNS, sizeof t[u][0], cores_cmp);
        *other = t[0][CORES_RUNS / 2] * 1e9;
        *own = t[1][CORES_RUNS / 2] * 1e9;
        *shared = t[2][CORES_RUNS / 2] * 1e9;
        *shared_shuffled = t[3][CORES_RUNS / 2] * 1e9;
    }
    free(cores_lines);
    free(cores_order);
    cores_lines = NULL;
    cores_order = NULL;
    return ok;
}

void bench_cores_line(FILE *f, const char *when)
{
    double trip = bench_cores_round_trip_ns(), other = 0, own = 0, shared = 0, shuffled = 0, fast = 0, slow = 0;
    if (trip > 0 && bench_cores_lines_ns(&other, &own, &shared, &shuffled) && bench_cores_speeds_ns(&fast, &slow))
        fprintf(f, "machine %s: a cache line to the other core and back %.0f ns; reading lines the other core "
                "has just written %.1f ns a line, its own %.1f; writing lines the other core has just read "
                "%.1f in order, %.1f at random; the two threads' speeds at once %.2fx apart\n",
                when, trip, other, own, shared, shuffled, slow / fast);
    else if (sysconf(_SC_NPROCESSORS_ONLN) > 1)
        fprintf(f, "machine %s: two threads did not run at once (another load on the cpus?)\n", when);
}
