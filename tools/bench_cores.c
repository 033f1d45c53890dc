/* bench_cores.c: what moving data between two cores costs on this machine, for the bench's
 * machine line.  Two threads hand a counter back and forth, each waiting (spinning) for the
 * other's write: one round trip is a cache line gone to the other core and back.  A step
 * spread over workers moves its data between cores stage after stage, so what a second
 * worker gains depends on this (README, Known limits). */
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

static uint64_t cores_counter; /* odd: the main thread's turn is over; even: the other's */

static void *cores_other(void *arg)
{
    (void)arg;
    for (uint64_t i = 0; i < CORES_TRIPS; i++) {
        while (__atomic_load_n(&cores_counter, __ATOMIC_ACQUIRE) != 2 * i + 1) {
        }
        __atomic_store_n(&cores_counter, 2 * i + 2, __ATOMIC_RELEASE);
    }
    return NULL;
}

static int cores_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_cores_round_trip_ns(void)
{
    if (sysconf(_SC_NPROCESSORS_ONLN) < 2) return -1; /* the two threads would take turns */
    double t[CORES_RUNS];
    for (int r = 0; r < CORES_RUNS; r++) {
        pthread_t other;
        __atomic_store_n(&cores_counter, 0, __ATOMIC_RELEASE);
        if (pthread_create(&other, NULL, cores_other, NULL) != 0) return -1;
        struct timespec a, b;
        clock_gettime(CLOCK_MONOTONIC, &a);
        for (uint64_t i = 0; i < CORES_TRIPS; i++) {
            __atomic_store_n(&cores_counter, 2 * i + 1, __ATOMIC_RELEASE);
            while (__atomic_load_n(&cores_counter, __ATOMIC_ACQUIRE) != 2 * i + 2) {
            }
        }
        clock_gettime(CLOCK_MONOTONIC, &b);
        pthread_join(other, NULL);
        t[r] = ((double)(b.tv_sec - a.tv_sec) * 1e9 + (double)(b.tv_nsec - a.tv_nsec)) / CORES_TRIPS;
    }
    qsort(t, CORES_RUNS, sizeof t[0], cores_cmp);
    return t[CORES_RUNS / 2];
}
