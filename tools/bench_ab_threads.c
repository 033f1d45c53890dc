/* bench_ab_threads.c: two builds of the library side by side in one process, each stepping
 * the same scene with two workers and with one: a comparison of like with like for a change
 * to the threaded step, on a machine whose speed drifts between runs and whose two cores now
 * share a line in some 100 ns and now in 500 (bench_cores.c): the worlds step in turns, so
 * the steps compared are neighbours in time.
 *
 * This build makes the scene (tools/bench_scenes.c, sleeping off) and saves it before its
 * first step; A and B (shared libraries of builds of the same snapshot format) each restore
 * it into a world stepped on one thread and a world stepped on a pool of two threads.  The
 * pool is A's, and both builds' two-worker worlds use it (the task system is a plain table
 * of functions): two pools would spin against each other.  Each round steps the four worlds
 * in a random order (a world that always followed another two-worker world would find the
 * pool's thread awake).  Prints each world's median step over the second half, the median
 * and quartiles of B's step over A's round by round, at two workers and at one, and whether
 * the four worlds end in one state (rg_world_hash), with the machine line of bench_cores.c
 * before and after (what moving data between the cores costs then, and the two threads'
 * speeds).
 *   build/bench-ab-threads A.so B.so [SCENE [N [STEPS]]]   (defaults boxes 10000 300) */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, dlopen */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "bench_run.h"
#include "rigid.h"

/* The calls of one build, through dlsym. */
typedef struct abt_build {
    rg_status (*create)(rg_world **);
    rg_status (*restore)(rg_world *, const void *, size_t);
    rg_status (*set_tasks)(rg_world *, const rg_task_system *);
    rg_status (*step)(rg_world *, rg_real);
    rg_status (*hash)(const rg_world *, uint64_t *);
    rg_status (*pool_create)(int32_t, rg_thread_pool **);
    rg_status (*pool_tasks)(rg_thread_pool *, rg_task_system *);
} abt_build;

/* An object pointer made a function pointer through its bytes (ISO C has no cast for it). */
#define ABT_SYM(lib, fn, name)                                   \
    do {                                                         \
        void *p_ = dlsym((lib), (name));                         \
        if (p_ == NULL || sizeof(p_) != sizeof(fn)) return 0;    \
        memcpy(&(fn), &p_, sizeof(fn));                          \
    } while (0)

static int abt_load(abt_build *b, const char *path)
{
    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (lib == NULL) {
        fprintf(stderr, "bench-ab-threads: %s\n", dlerror());
        return 0;
    }
    ABT_SYM(lib, b->create, "rg_world_create");
    ABT_SYM(lib, b->restore, "rg_world_restore");
    ABT_SYM(lib, b->set_tasks, "rg_world_set_task_system");
    ABT_SYM(lib, b->step, "rg_world_step");
    ABT_SYM(lib, b->hash, "rg_world_hash");
    ABT_SYM(lib, b->pool_create, "rg_thread_pool_create");
    ABT_SYM(lib, b->pool_tasks, "rg_thread_pool_task_system");
    return 1;
}

static double abt_now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int abt_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: bench-ab-threads A.so B.so [SCENE [N [STEPS]]]\n");
        return 2;
    }
    const char *name = argc > 3 ? argv[3] : "boxes";
    int n = argc > 4 ? atoi(argv[4]) : 10000, steps = argc > 5 ? atoi(argv[5]) : 300;
    const bench_scene_def *kind = bench_scene_find(name);
    if (kind == NULL || n < 1 || steps < 8) {
        fprintf(stderr, "bench-ab-threads: a scene of tools/bench_scenes.c, N >= 1, STEPS >= 8\n");
        return 2;
    }
    /* the scene before its first step, saved by this build */
    bench_scene s;
    if (!bench_scene_build(&s, kind, n)) return 1;
    s.sleep = 0;
    s.workers = 1;
    void *e = bench_rigid_engine.create(&s);
    if (e == NULL) return 1;
    size_t size = bench_rigid_engine.save(e, NULL, 0);
    void *snap = malloc(size);
    if (snap == NULL || bench_rigid_engine.save(e, snap, size) != size) return 1;
    bench_rigid_engine.destroy(e);
    /* worlds 0 and 1: A and B on two workers; 2 and 3: A and B on one */
    abt_build build[2];
    for (int k = 0; k < 2; k++)
        if (!abt_load(&build[k], argv[1 + k])) {
            fprintf(stderr, "bench-ab-threads: %s lacks a call this tool needs\n", argv[1 + k]);
            return 1;
        }
    rg_thread_pool *pool;
    rg_task_system tasks;
    bench_cores_line(stdout, "before");
    if (build[0].pool_create(2, &pool) != RG_OK || build[0].pool_tasks(pool, &tasks) != RG_OK) return 1;
    rg_world *w[4];
    for (int k = 0; k < 4; k++) {
        const abt_build *b = &build[k & 1];
        if (b->create(&w[k]) != RG_OK || b->restore(w[k], snap, size) != RG_OK ||
            b->set_tasks(w[k], k < 2 ? &tasks : NULL) != RG_OK) {
            fprintf(stderr, "bench-ab-threads: %s cannot restore this build's snapshot\n", argv[1 + (k & 1)]);
            return 1;
        }
    }
    double *t = malloc(6 * (size_t)steps * sizeof *t);
    if (t == NULL) return 1;
    uint64_t seed = 0x9E3779B97F4A7C15ull;
    for (int q = 0; q < steps; q++) {
        int order[4] = { 0, 1, 2, 3 };
        for (int j = 3; j > 0; j--) { /* Fisher-Yates */
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            int r = (int)((seed >> 33) % (uint64_t)(j + 1)), x = order[j];
            order[j] = order[r];
            order[r] = x;
        }
        for (int j = 0; j < 4; j++) {
            int k = order[j];
            double a = abt_now_ms();
            if (build[k & 1].step(w[k], (rg_real)(1.0 / 60)) != RG_OK) return 1;
            t[k * steps + q] = abt_now_ms() - a;
        }
    }
    bench_cores_line(stdout, "after"); /* the pool's thread sleeps within a millisecond */
    /* the second half: the pile formed */
    int h = steps / 2, c = steps - h;
    double *r2 = t + 4 * (size_t)steps, *r1 = r2 + c, med[4];
    for (int q = 0; q < c; q++) {
        r2[q] = t[1 * steps + h + q] / t[0 * steps + h + q];
        r1[q] = t[3 * steps + h + q] / t[2 * steps + h + q];
    }
    qsort(r2, (size_t)c, sizeof *r2, abt_cmp);
    qsort(r1, (size_t)c, sizeof *r1, abt_cmp);
    for (int k = 0; k < 4; k++) {
        qsort(t + k * steps + h, (size_t)c, sizeof *t, abt_cmp);
        med[k] = t[k * steps + h + c / 2];
    }
    uint64_t hash[4];
    for (int k = 0; k < 4; k++)
        if (build[k & 1].hash(w[k], &hash[k]) != RG_OK) return 1;
    int same = hash[0] == hash[1] && hash[1] == hash[2] && hash[2] == hash[3];
    printf("%s %d, %d steps in turns, medians of the last %d: two workers A %.3f ms, B %.3f; one worker A %.3f, "
           "B %.3f\n  B/A step by step: two workers %.3f (%.3f-%.3f), one worker %.3f (%.3f-%.3f); two workers "
           "over one: A %.2f, B %.2f; %s\n",
           name, n, steps, c, med[0], med[1], med[2], med[3], r2[c / 2], r2[c / 4], r2[3 * c / 4], r1[c / 2],
           r1[c / 4], r1[3 * c / 4], med[0] / med[2], med[1] / med[3],
           same ? "the four worlds end in one state" : "THE WORLDS END IN DIFFERENT STATES");
    free(t);
    free(snap);
    return same ? 0 : 1;
}
