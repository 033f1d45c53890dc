/* bench_snapshot.c: what a snapshot costs, rigid beside Box2D v3 (b2World_Snapshot,
 * b2World_Restore, b2World_GetStateHash) in the same run: bytes per body, and microseconds
 * to save, to restore and to hash, for the bench's rain scene (tools/bench_scenes.c,
 * sleeping on) at N = 1000 and 10000, taken while the pile is still moving (step 60) and
 * once it rests (step 600). Each engine restores into a second world built from the same
 * scene, and the restored world's hash must equal the saved one's (for rigid a snapshot
 * from outside, checked whole). Then the rollback a game makes: the world saves, steps 8
 * frames and restores (for rigid also with a kept state, which v3 has no counterpart of),
 * the step not timed: rigid's world restores its own save, which from the second time on it
 * knows again and loads unchecked (src/own.h), as every rollback after a game's first does;
 * and, like for like, the same state saved by another world (its own handle tag: checked
 * whole). Then a whole rollback of 8 frames as the game pays for it in the frame where a
 * late input arrives: back to the state of 8 frames ago, and each of the 8 frames saved
 * again and stepped, timed as one, against a 60 Hz frame's 16.7 ms. Medians of 31 timings
 * each. Then rigid again with its pool of two threads (rigid-2w), which its restore spreads
 * over.
 *   build/bench-snapshot [--v3 DIR|none] [N ...] */
#define _GNU_SOURCE 1 /* mallopt */
#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"

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

/* The rollback pattern: save (or keep) at a frame, step ROLLBACK frames, restore (or go
 * back); each time from the same frame, whose hash the restored world must have.  The save
 * is the world's own (ROLL_OWN; rigid knows it again from the second time on: unchecked),
 * a kept state (ROLL_KEPT), or the snapshot of another world in the same state (ROLL_OTHER,
 * src: for rigid a snapshot from outside, checked whole), the same bytes but the handle tag
 * (the restore takes src's).
 * Medians of REPS; 0 when a call failed or the hash differed. */
#define ROLLBACK 8
enum { ROLL_OWN, ROLL_OTHER, ROLL_KEPT };
static int rollback(const bench_engine *e, void *w, void *src, void *buf, size_t size, int mode, double *save,
                    double *restore)
{
    double ts[REPS], tr[REPS];
    uint64_t h = e->hash(w);
    for (int r = 0; r < REPS; r++) {
        double t0 = now();
        int ok = mode == ROLL_KEPT ? e->keep(w, 0) : e->save(mode == ROLL_OTHER ? src : w, buf, size) == size;
        double t1 = now();
        for (int k = 0; k < ROLLBACK; k++) e->step(w, 1.0 / 60.0);
        double t2 = now();
        ok = ok && (mode == ROLL_KEPT ? e->back(w, 0) : e->restore(w, buf, size));
        double t3 = now();
        if (!ok || e->hash(w) != h) return 0;
        ts[r] = t1 - t0;
        tr[r] = t3 - t2;
    }
    *save = median(ts, REPS);
    *restore = median(tr, REPS);
    return 1;
}

/* The whole rollback: the state of ROLLBACK frames ago brought back (ring[0], or slot 0),
 * then each frame saved again into the ring (or slot k) and stepped; restore + ROLLBACK x
 * (save + step) timed as one, the median of REPS in *total.  ring[k] holds up to cap bytes.
 * Every repetition starts from the same state (slot 0 is saved again with it), whose hash
 * the restored world must have; 0 when a call failed or the hash differed. */
static int resimulate(const bench_engine *e, void *w, unsigned char **ring, size_t cap, int kept, double *total)
{
    double t[REPS];
    size_t size[ROLLBACK];
    uint64_t h = e->hash(w);
    size[0] = kept ? 0 : e->save(w, ring[0], cap);
    if (kept ? !e->keep(w, 0) : size[0] == 0 || size[0] > cap) return 0;
    for (int r = 0; r < REPS; r++) {
        double t0 = now();
        int ok = kept ? e->back(w, 0) : e->restore(w, ring[0], size[0]);
        for (int k = 0; k < ROLLBACK && ok; k++) {
            if (kept) {
                ok = e->keep(w, k);
            } else {
                size[k] = e->save(w, ring[k], cap);
                ok = size[k] > 0 && size[k] <= cap;
            }
            e->step(w, 1.0 / 60.0);
        }
        t[r] = now() - t0;
        if (!ok) return 0;
        /* back where this repetition began, untimed, to check it came back exactly */
        if (!(kept ? e->back(w, 0) : e->restore(w, ring[0], size[0])) || e->hash(w) != h) return 0;
    }
    *total = median(t, REPS);
    return 1;
}

/* 0 when the engine cannot save or restore this world. */
static int measure(const bench_engine *e, const char *name, const bench_scene *s, int steps)
{
    void *w = e->create(s), *target = e->create(s);
    if (w == NULL || target == NULL) {
        if (w != NULL) e->destroy(w);
        if (target != NULL) e->destroy(target);
        return 0;
    }
    for (int k = 0; k < steps; k++) e->step(w, 1.0 / 60.0);
    size_t size = e->save(w, NULL, 0);
    void *buf = size > 0 ? malloc(size) : NULL;
    double ts[REPS], tr[REPS], th[REPS];
    uint64_t h = 0;
    int ok = buf != NULL;
    for (int r = 0; r < REPS && ok; r++) {
        double t0 = now();
        ok = e->save(w, buf, size) == size;
        double t1 = now();
        ok = ok && e->restore(target, buf, size);
        double t2 = now();
        h = e->hash(w);
        double t3 = now();
        ts[r] = t1 - t0;
        tr[r] = t2 - t1;
        th[r] = t3 - t2;
    }
    if (ok) {
        int same = e->hash(target) == h;
        double save = median(ts, REPS), restore = median(tr, REPS);
        printf("%-10s rain %6d  step %3d  %8.1f KB  %6.0f B/body  save %7.1f us  restore %7.1f us  "
               "hash %7.1f us  save+restore %7.1f us%s\n",
               name, (int)s->size, steps, (double)size / 1024, (double)size / s->nbodies, save * 1e6,
               restore * 1e6, median(th, REPS) * 1e6, (save + restore) * 1e6, same ? "" : "  HASH DIFFERS");
    } else {
        printf("%-10s rain %6d  step %3d  the snapshot failed\n", name, (int)s->size, steps);
    }
    /* the other world: built and stepped as w was, so in its state, but with a handle tag of
     * its own (target, restored from w's bytes, would save those very bytes, which w knows) */
    void *twin = ok ? e->create(s) : NULL;
    for (int k = 0; k < steps && twin != NULL; k++) e->step(twin, 1.0 / 60.0);
    ok = ok && twin != NULL;
    static const char *const how[] = { "own snapshot:", "other's:", "kept in a slot:" };
    for (int mode = ROLL_OWN; mode <= (e->keep != NULL ? ROLL_KEPT : ROLL_OTHER) && ok; mode++) {
        double save, restore;
        ok = rollback(e, w, twin, buf, size, mode, &save, &restore);
        if (ok)
            printf("%-10s rain %6d  step %3d  rollback of %d steps, %-15s save %7.1f us  restore %7.1f us  "
                   "save+restore %7.1f us\n",
                   name, (int)s->size, steps, ROLLBACK, how[mode], save * 1e6, restore * 1e6, (save + restore) * 1e6);
        else
            printf("%-10s rain %6d  step %3d  the rollback failed\n", name, (int)s->size, steps);
    }
    /* the ring of the whole rollback: room for a state twice this one's size */
    unsigned char *ring[ROLLBACK];
    int have = 0;
    for (; have < ROLLBACK && ok; have++)
        if ((ring[have] = malloc(2 * size)) == NULL) break;
    ok = ok && have == ROLLBACK;
    for (int kept = 0; kept <= (e->keep != NULL) && ok; kept++) {
        double total;
        ok = resimulate(e, w, ring, 2 * size, kept, &total);
        if (ok)
            printf("%-10s rain %6d  step %3d  rollback of %d frames resimulated, %-14s %6.2f ms (restore + %d x (save + "
                   "step)): %3.0f%% of a 60 Hz frame\n",
                   name, (int)s->size, steps, ROLLBACK, kept ? "kept in slots:" : "snapshots:", total * 1e3, ROLLBACK,
                   total * 1e3 / (1000.0 / 60.0) * 100);
        else
            printf("%-10s rain %6d  step %3d  the resimulated rollback failed\n", name, (int)s->size, steps);
    }
    for (int k = 0; k < have; k++) free(ring[k]);
    if (twin != NULL) e->destroy(twin);
    free(buf);
    e->destroy(target);
    e->destroy(w);
    return ok;
}

int main(int argc, char **argv)
{
    int sizes[8] = { 1000, 10000 }, ns = 2, given = 0;
    const char *v3_dir = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--v3") == 0 && i + 1 < argc) {
            v3_dir = argv[++i];
        } else {
            int n = atoi(argv[i]);
            if (n < 1 || n > 1000000) {
                fprintf(stderr, "usage: bench-snapshot [--v3 DIR|none] [N ...]\n");
                return 2;
            }
            if (!given) ns = 0;
            given = 1;
            if (ns < 8) sizes[ns++] = n;
        }
    }
    /* glibc's adaptive mmap threshold otherwise makes a v3 save (which grows a buffer of its
     * own to the image's size each time) cost 4x more in one engine than in another,
     * depending on what ran before: large blocks come from the heap for everyone. */
    mallopt(M_MMAP_THRESHOLD, 256 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
    const bench_engine *v3[2], *engines[3] = { &bench_rigid_engine, NULL, NULL };
    char why[1024];
    bench_v3_load(v3_dir, v3, why, sizeof why);
    int ne = 1;
    for (int b = 0; b < 2; b++)
        if (v3[b] != NULL) engines[ne++] = v3[b];
    printf("snapshots: the bench's rain (sleeping on); medians of %d timings; B/body counts every body "
           "(static too); restore: into a second world of the scene (rigid: checked whole); rollback, own "
           "snapshot: rigid knows it again (unchecked); other's: saved by a world in the same state (checked)\nengines:", REPS);
    for (int k = 0; k < ne; k++) printf(" [%s]", engines[k]->version());
    printf("\n");
    if (why[0] != 0) printf("(%s)\n", why);
    const bench_scene_def *d = bench_scene_find("rain");
    int failed = 0;
    for (int i = 0; i < ns; i++) {
        bench_scene s;
        if (d == NULL || !bench_scene_build(&s, d, sizes[i])) return 1;
        s.sleep = 1;
        for (int k = 0; k < ne; k++) {
            failed |= !measure(engines[k], engines[k]->name, &s, 60);
            failed |= !measure(engines[k], engines[k]->name, &s, 600);
        }
#ifdef RG_BENCH_THREADS
        /* rigid's restore spreads its checks and load over the world's task system: the
         * same worlds with rigid's pool of two threads (v3's snapshot has no threads) */
        s.workers = 2;
        failed |= !measure(&bench_rigid_engine, "rigid-2w", &s, 60);
        failed |= !measure(&bench_rigid_engine, "rigid-2w", &s, 600);
        s.workers = 1;
#endif
        free(s.bodies);
    }
    return failed;
}
