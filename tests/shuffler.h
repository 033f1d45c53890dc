/* shuffler.h: a task system (rg_task_system) that does to a task what threads would do to
 * its split and its order, deterministically, for the thread tests and the fuzzers.  Each
 * task is cut into ranges of random lengths (min_range to 3 * min_range, the last one
 * shorter when the count ends there), which run in a random order with random worker indices
 * in [0, workers), when finish is called (deferred: enqueue returns the task) or, eager, at
 * once in enqueue, which then returns NULL (both are allowed by rigid.h).  What the world
 * must not do (enqueue with a task pending, finish a task it was not given, a count or a
 * min_range below 1) is counted in `misuse`. */
#ifndef RG_SHUFFLER_H
#define RG_SHUFFLER_H

#include <stdint.h>

#include "rigid.h"

typedef struct shuffler {
    uint64_t seed;
    int32_t workers;
    int eager;
    /* the deferred task */
    rg_task_fn *fn;
    int32_t count, min_range;
    void *context;
    long tasks, ranges, misuse;
} shuffler;

static inline void shuffler_init(shuffler *s, uint64_t seed, int32_t workers, int eager)
{
    s->seed = seed;
    s->workers = workers;
    s->eager = eager;
    s->fn = NULL;
    s->count = s->min_range = 0;
    s->context = NULL;
    s->tasks = s->ranges = s->misuse = 0;
}

static inline uint32_t shuffler_next(shuffler *s)
{
    s->seed = s->seed * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(s->seed >> 33);
}

static inline void shuffler_run(shuffler *s, rg_task_fn *fn, int32_t count, int32_t min_range, void *context)
{
    enum { MAXR = 4096 };
    static int32_t begin[MAXR], end[MAXR];
    int32_t n = 0;
    for (int32_t at = 0; at < count;) {
        int32_t len = min_range + (int32_t)(shuffler_next(s) % (uint32_t)(2 * min_range + 1));
        if (n == MAXR - 1 || len > count - at) len = count - at;
        begin[n] = at;
        end[n++] = at + len;
        at += len;
    }
    for (int32_t k = n - 1; k > 0; k--) { /* Fisher-Yates */
        int32_t j = (int32_t)(shuffler_next(s) % (uint32_t)(k + 1));
        int32_t tb = begin[k], te = end[k];
        begin[k] = begin[j];
        end[k] = end[j];
        begin[j] = tb;
        end[j] = te;
    }
    for (int32_t k = 0; k < n; k++)
        fn(begin[k], end[k], (int32_t)(shuffler_next(s) % (uint32_t)s->workers), context);
    s->ranges += n;
}

static inline void *shuffler_enqueue(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user)
{
    shuffler *s = (shuffler *)user;
    s->tasks++;
    if (count < 1 || min_range < 1 || s->fn != NULL) {
        s->misuse++;
        return NULL;
    }
    if (s->eager) {
        shuffler_run(s, fn, count, min_range, context);
        return NULL;
    }
    s->fn = fn;
    s->count = count;
    s->min_range = min_range;
    s->context = context;
    return s;
}

static inline void shuffler_finish(void *task, void *user)
{
    shuffler *s = (shuffler *)user;
    if (task != s || s->fn == NULL) {
        s->misuse++;
        return;
    }
    rg_task_fn *fn = s->fn;
    s->fn = NULL;
    shuffler_run(s, fn, s->count, s->min_range, s->context);
}

/* The task system of s, for rg_world_set_task_system. */
static inline void shuffler_tasks(shuffler *s, rg_task_system *out)
{
    out->workers = s->workers;
    out->enqueue = shuffler_enqueue;
    out->finish = shuffler_finish;
    out->user = s;
}

#endif
