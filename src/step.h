/* step.h: optional phase timers of the step for development: build with
 * -DRG_STEP_PROFILE -D_POSIX_C_SOURCE=199309L (a POSIX clock); they print to stderr every ten
 * steps, with the solve's parts on one thread (resolve.c), and every hundred steps the
 * tasks' times and each worker's inside them (task.h; the solve's passes over rows and
 * bodies each under its own name).  Without it they compile to nothing.
 * E.g. make B=build/prof EXTRA_CFLAGS="-DRG_STEP_PROFILE -D_POSIX_C_SOURCE=199309L"
 * build/prof/bench-peers, then build/prof/bench-peers --v3 none --engine rigid-2w --sleep off
 * --scene boxes:10000 --repeats 1. */
#ifndef RG_STEP_H
#define RG_STEP_H

#ifdef RG_STEP_PROFILE
#include <stdio.h>
#include <string.h>
#include <time.h>
#include "task.h"
static double step_prof_acc[8], step_prof_last, step_prof_moved;
static double step_prof_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}
#define STEP_PROF_MOVED(n) (step_prof_moved += (n))
#define STEP_PROF(k)                                                          \
    do {                                                                      \
        double t_ = step_prof_now();                                          \
        if ((k) >= 0) step_prof_acc[(k)] += t_ - step_prof_last;              \
        step_prof_last = t_;                                                  \
    } while (0)
#define STEP_PROF_REPORT(w, x)                                                                 \
    do {                                                                                       \
        if ((w)->step_count % 10 == 9) {                                                      \
            fprintf(stderr, "contacts %d rows %d active %d | ms/step:", (w)->coll.contacts.n_awake, \
                    (x).nc, (w)->coll.bp.n_active);                                            \
            const char *names_[] = {"views", "pairs", "narrow", "solve", "sweep+fat", "sleep"}; \
            for (int q_ = 0; q_ < 6; q_++) fprintf(stderr, " %s %.3f", names_[q_], step_prof_acc[q_] * 1e3 / 10); \
            fprintf(stderr, " moved/step %.0f | solve on one thread, ms/step: order %.3f colour %.3f shock %.3f\n", \
                    step_prof_moved / 10, step_prof_solve[0] * 1e3 / 10, step_prof_solve[1] * 1e3 / 10,            \
                    step_prof_solve[2] * 1e3 / 10);                                                                 \
            if ((w)->step_count % 100 == 99) task_prof_report(stderr, 100);                    \
            step_prof_moved = 0;                                                               \
            memset(step_prof_solve, 0, sizeof step_prof_solve);                                \
            memset(step_prof_acc, 0, sizeof step_prof_acc);                                    \
        }                                                                                      \
    } while (0)
#else
#define STEP_PROF(k) ((void)0)
#define STEP_PROF_MOVED(n) ((void)0)
#define STEP_PROF_REPORT(w, x) ((void)0)
#endif

#endif
