/* bench_cores.c: what moving data between two cores costs on this machine, for the bench's
 * machine line.  Two threads hand a counter back and forth, each waiting (spinning) for the
 * other's write: one round trip is a cache line gone to the other core and back.  A step
 * spread over workers moves its data between cores stage after stage, so what a second
 * worker gains depends on this (README, Known limits).  Where the two threads cannot run at
 * once (one cpu, or under valgrind, which runs one thread at a time and would take hours
 * over the spins) the hand-overs stop at a deadline and nothing is reported. */
#undef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdint.h>
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

static void *cores_other(void *arg)
{
    (void)arg;
    for (uint64_t i = 0; i < CORES_TRIPS; i++) {
        while (__atomic_load_n(&cores_counter, __ATOMIC_ACQUIRE) != 2 * i + 1)
            if (__atomic_load_n(&cores_stop, __ATOMIC_RELAXED)) return NULL;
        __atomic_store_n(&cores_counter, 2 * i + 2, __ATOMIC_RELEASE);
    }
    return NULL;
}

/* One run's time a round trip, s; -1 past the deadline. */
static double cores_run(void)
{
    pthread_t other;
    __atomic_store_n(&cores_counter, 0, __ATOMIC_RELEASE);
    __atomic_store_n(&cores_stop, 0, __ATOMIC_RELEASE);
    if (pthread_create(&other, NULL, cores_other, NULL) != 0) return -1;
    double t0 = cores_now(), t = -1;
    uint64_t i = 0;
    for (; i < CORES_TRIPS; i++) {
        __atomic_store_n(&cores_counter, 2 * i + 1, __ATOMIC_RELEASE);
        for (uint32_t spins = 1; __atomic_load_n(&cores_counter, __ATOMIC_ACQUIRE) != 2 * i + 2; spins++)
            if (spins % 4096 == 0 && cores_now() - t0 > CORES_DEADLINE_S) break;
        if (__atomic_load_n(&cores_counter, __ATOMIC_ACQUIRE) != 2 * i + 2) break;
    }
    if (i == CORES_TRIPS) t = (cores_now() - t0) / CORES_TRIPS;
    __atomic_store_n(&cores_stop, 1, __ATOMIC_RELEASE);
    pthread_join(other, NULL);
    return t;
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
