/* bench_ab.c: two builds of the library, side by side in one process, restoring the same
 * snapshot of the bench's rain (tools/bench_scenes.c, sleeping on) in turns, A then B, B
 * then A: a comparison of like with like on a machine whose speed drifts between runs (a
 * VM whose phases move every figure by 1.5x moves both sides of each pair alike).  The
 * snapshot is made by this build (the bench's rigid engine); A and B are shared libraries
 * of builds of the same snapshot format (rg_world_restore must accept it), loaded with
 * dlopen, each restoring into a world of its own.  Prints the median time of each and the
 * median and quartiles of B's time over A's, pair by pair.
 *   build/bench-ab A.so B.so [N [STEPS [PAIRS]]]   (defaults 10000 60 400) */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, dlopen */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"

typedef int (*ab_create_fn)(void **world);
typedef int (*ab_restore_fn)(void *world, const void *data, size_t size);

static double ab_now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e6 + (double)t.tv_nsec * 1e-3;
}

static int ab_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: bench-ab A.so B.so [N [STEPS [PAIRS]]]\n");
        return 2;
    }
    int n = argc > 3 ? atoi(argv[3]) : 10000, steps = argc > 4 ? atoi(argv[4]) : 60;
    int pairs = argc > 5 ? atoi(argv[5]) : 400;
    if (n < 1 || steps < 0 || pairs < 4) {
        fprintf(stderr, "bench-ab: N >= 1, STEPS >= 0, PAIRS >= 4\n");
        return 2;
    }
    /* the snapshot, made by this build */
    bench_scene s;
    if (!bench_scene_build(&s, bench_scene_find("rain"), n)) return 1;
    s.sleep = 1;
    const bench_engine *e = &bench_rigid_engine;
    void *w = e->create(&s);
    if (w == NULL) return 1;
    for (int k = 0; k < steps; k++) e->step(w, 1.0 / 60);
    size_t size = e->save(w, NULL, 0);
    void *snap = malloc(size);
    if (snap == NULL || e->save(w, snap, size) != size) return 1;
    e->destroy(w);
    /* each build's world, restored once before the timings */
    void *world[2];
    ab_restore_fn restore[2];
    for (int k = 0; k < 2; k++) {
        void *lib = dlopen(argv[1 + k], RTLD_NOW | RTLD_LOCAL);
        if (lib == NULL) {
            fprintf(stderr, "bench-ab: %s\n", dlerror());
            return 1;
        }
        void *c = dlsym(lib, "rg_world_create"), *r = dlsym(lib, "rg_world_restore");
        ab_create_fn create = NULL;
        if (c != NULL && r != NULL) { /* object pointers made function pointers through their bytes */
            memcpy(&create, &c, sizeof create);
            memcpy(&restore[k], &r, sizeof restore[k]);
        }
        if (create == NULL || create(&world[k]) != 0 || restore[k](world[k], snap, size) != 0) {
            fprintf(stderr, "bench-ab: %s cannot restore this build's snapshot\n", argv[1 + k]);
            return 1;
        }
    }
    double *t = malloc(3 * (size_t)pairs * sizeof *t);
    if (t == NULL) return 1;
    double *ta = t, *tb = t + pairs, *ratio = t + 2 * pairs;
    for (int i = 0; i < pairs; i++) {
        for (int j = 0; j < 2; j++) {
            int k = (i & 1) ? 1 - j : j;
            double a = ab_now_us();
            if (restore[k](world[k], snap, size) != 0) return 1;
            (k ? tb : ta)[i] = ab_now_us() - a;
        }
        ratio[i] = tb[i] / ta[i];
    }
    qsort(ta, (size_t)pairs, sizeof *ta, ab_cmp);
    qsort(tb, (size_t)pairs, sizeof *tb, ab_cmp);
    qsort(ratio, (size_t)pairs, sizeof *ratio, ab_cmp);
    printf("rain %d, step %d, %d pairs of restores: A median %.1f us, B median %.1f us; "
           "B/A pair by pair: median %.3f, quartiles %.3f-%.3f\n",
           n, steps, pairs, ta[pairs / 2], tb[pairs / 2], ratio[pairs / 2], ratio[pairs / 4], ratio[3 * pairs / 4]);
    free(t);
    free(snap);
    return 0;
}
