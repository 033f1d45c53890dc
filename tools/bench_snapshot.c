/* bench_snapshot.c: what a snapshot costs: bytes per body, and microseconds to save, to
 * restore and to hash, for the bench's rain scene (circles r 0.5 dropped on a 1.1 m grid into
 * a container, as tools/bench.c builds it) at N = 1000 and 10000, taken while the pile is
 * still moving (step 60) and once it rests (step 600).  Medians of 31 timings each.
 *   build/bench-snapshot [N ...] */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rigid.h"

#define REPS 31

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    return v[n / 2];
}

static rg_body make(rg_world *w, int32_t type, double x, double y, double hw, double hh, int circle)
{
    rg_body b;
    rg_body_create(w, type, 1, (rg_vec2){ (rg_real)x, (rg_real)y }, &b);
    if (circle)
        rg_body_set_circle(w, b, (rg_real)hw);
    else
        rg_body_set_aabb(w, b, (rg_real)hw, (rg_real)hh);
    return b;
}

/* The bench's rain: a container as wide as a square grid of the bodies, 1.1 m apart. */
static rg_world *rain(int n)
{
    rg_world *w;
    rg_world_create(&w);
    rg_world_set_gravity(w, (rg_vec2){ 0, -10 });
    int cols = (int)ceil(sqrt((double)n));
    double width = cols * 1.1 + 1;
    make(w, RG_BODY_STATIC, 0, -0.5, width / 2 + 1, 0.5, 0);
    make(w, RG_BODY_STATIC, -width / 2 - 0.5, 40, 0.5, 40, 0);
    make(w, RG_BODY_STATIC, width / 2 + 0.5, 40, 0.5, 40, 0);
    for (int i = 0; i < n; i++) {
        double x = -width / 2 + 1 + (i % cols) * 1.1 + 0.01 * (i % 7);
        double y = 1 + (i / cols) * 1.1;
        make(w, RG_BODY_DYNAMIC, x, y, 0.5, 0.5, 1);
    }
    return w;
}

static void measure(int n, int steps)
{
    rg_world *w = rain(n), *target;
    rg_world_create(&target);
    for (int k = 0; k < steps; k++) rg_world_step(w, 1.0f / 60);
    size_t size;
    rg_world_save(w, NULL, 0, &size);
    void *buf = malloc(size);
    double ts[REPS], tr[REPS], th[REPS];
    uint64_t h = 0, h2 = 0;
    rg_world_restore(target, buf, 0); /* refused: nothing */
    for (int r = 0; r < REPS; r++) {
        double t0 = now();
        rg_world_save(w, buf, size, &size);
        double t1 = now();
        rg_status st = rg_world_restore(target, buf, size);
        double t2 = now();
        rg_world_hash(w, &h);
        double t3 = now();
        if (st != RG_OK) {
            fprintf(stderr, "bench-snapshot: restore: %s\n", rg_status_string(st));
            exit(1);
        }
        ts[r] = t1 - t0;
        tr[r] = t2 - t1;
        th[r] = t3 - t2;
    }
    rg_world_hash(target, &h2);
    printf("rain %6d  step %3d  %8.1f KB  %6.0f B/body  save %7.1f us  restore %7.1f us  hash %7.1f us  "
           "save+restore %7.1f us%s\n",
           n, steps, (double)size / 1024, (double)size / (n + 3), median(ts, REPS) * 1e6, median(tr, REPS) * 1e6,
           median(th, REPS) * 1e6, (median(ts, REPS) + median(tr, REPS)) * 1e6, h == h2 ? "" : "  HASH DIFFERS");
    free(buf);
    rg_world_destroy(target);
    rg_world_destroy(w);
}

int main(int argc, char **argv)
{
    int sizes[8] = { 1000, 10000 }, ns = 2;
    if (argc > 1) {
        ns = 0;
        for (int i = 1; i < argc && ns < 8; i++) sizes[ns++] = atoi(argv[i]);
    }
    printf("rigid snapshots (rg_real of %d bytes): medians of %d timings; B/body counts every body\n",
           (int)rg_real_size(), REPS);
    for (int i = 0; i < ns; i++) {
        measure(sizes[i], 60);
        measure(sizes[i], 600);
    }
    return 0;
}
