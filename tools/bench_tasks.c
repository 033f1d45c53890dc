/* bench_tasks.c: what each of a step's tasks gains from a second worker on this machine,
 * counted with what it costs the stages after it (which find its data where the other core
 * wrote it).  Three worlds of one scene (tools/bench_scenes.c, sleeping off) step in turns,
 * each step timed: one worker; two workers on rigid's pool of two threads; and two workers
 * whose task system runs one task of each step, the k-th (k = 0, 1, ...), inline on the
 * calling thread and hands the others to the pool.  Running task k alone inline measures
 * what spreading it gains where every other task is spread (a task alone on the pool would
 * also pay for moving the data the others leave on one core).  Results are the same
 * whichever thread runs a range, so the three worlds go through the same states (their
 * hashes are compared at the end), and each figure is a median of per-step ratios over the
 * second half of the run (the pile formed), with its quartiles: on a machine whose speed
 * drifts, the steps compared are neighbours in time.  Also two workers with every task
 * inline, against one worker: what the two-worker stages cost before any task is spread.
 * A task is named by its place in the step's order, its item count (median) and its
 * min_range (rigid's stages pass distinct ones).
 *   build/bench-tasks [SCENE:N ...] [--steps S]   (defaults boxes:10000 rain:10000, 400) */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "bench_run.h"
#include "rigid.h"

#define TASKS_MAX 128    /* tasks of a step told apart */
#define TASKS_STEPS 4000 /* most steps a run takes */
#define TASKS_ALL (-2)   /* every task inline */

/* The task system of the two-worker worlds: `held` is the index of the step's task that
 * runs inline (-1: none, TASKS_ALL: every one); log, when not NULL, records each index's
 * item count and min_range in the step `row`. */
typedef struct tasks_sys {
    rg_task_system sys;
    rg_task_system pool;
    int32_t call, held, row;
    int32_t (*log)[TASKS_MAX][2];
    int32_t most; /* the most tasks a step had */
} tasks_sys;

static void *tasks_enqueue(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user)
{
    tasks_sys *t = user;
    int32_t k = t->call++;
    if (k < TASKS_MAX && t->log != NULL) {
        t->log[t->row][k][0] = count;
        t->log[t->row][k][1] = min_range;
    }
    if (t->call > t->most) t->most = t->call;
    if (t->held == TASKS_ALL || t->held == k) {
        fn(0, count, 0, context);
    } else {
        void *h = t->pool.enqueue(fn, count, min_range, context, t->pool.user);
        if (h != NULL) t->pool.finish(h, t->pool.user);
    }
    return NULL;
}

static void tasks_finish(void *task, void *user)
{
    (void)task;
    (void)user;
}

static double tasks_now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e6 + (double)t.tv_nsec * 1e-3;
}

static int tasks_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median and quartiles of v[0, n) (sorted in place). */
static void tasks_quartiles(double *v, int n, double q[3])
{
    qsort(v, (size_t)n, sizeof *v, tasks_cmp);
    q[0] = v[n / 4];
    q[1] = v[n / 2];
    q[2] = v[(3 * n) / 4];
}

static int tasks_cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* A world of the scene; with t, two workers on t's task system. */
static void *tasks_world(bench_scene *s, tasks_sys *t)
{
    s->workers = 1;
    void *ctx = bench_rigid_engine.create(s);
    if (ctx == NULL || t == NULL) return ctx;
    t->sys.workers = 2;
    t->sys.enqueue = tasks_enqueue;
    t->sys.finish = tasks_finish;
    t->sys.user = t;
    if (rg_world_set_task_system(bench_rigid_world(ctx), &t->sys) != RG_OK) {
        bench_rigid_engine.destroy(ctx);
        return NULL;
    }
    return ctx;
}

/* Steps a one-worker world, a world whose tasks go to the pool but task held_b (b) and
 * one whose tasks go to the pool but task held_c (c) in turns; q_b: b's step over the one
 * worker's, q_c: c's over b's.  With log, c's tasks are recorded step by step. */
static int tasks_race(bench_scene *s, int steps, const rg_task_system *pool, int32_t held_b, int32_t held_c,
                      int32_t (*log)[TASKS_MAX][2], double q_b[3], double q_c[3], int32_t *most)
{
    tasks_sys tb = { 0 }, tc = { 0 };
    tb.pool = tc.pool = *pool;
    tb.held = held_b;
    tc.held = held_c;
    tc.log = log;
    void *a = tasks_world(s, NULL), *b = tasks_world(s, &tb), *c = tasks_world(s, &tc);
    int ok = a != NULL && b != NULL && c != NULL;
    int half = steps / 2, m = 0;
    double *rb = malloc((size_t)steps * sizeof *rb), *rc = malloc((size_t)steps * sizeof *rc);
    ok = ok && rb != NULL && rc != NULL;
    for (int k = 0; k < steps && ok; k++) {
        tb.call = tc.call = 0;
        tc.row = k;
        double t0 = tasks_now_us();
        bench_rigid_engine.step(a, 1.0 / 60.0);
        double t1 = tasks_now_us();
        bench_rigid_engine.step(b, 1.0 / 60.0);
        double t2 = tasks_now_us();
        bench_rigid_engine.step(c, 1.0 / 60.0);
        double t3 = tasks_now_us();
        if (k < half) continue;
        rb[m] = (t2 - t1) / (t1 - t0);
        rc[m] = (t3 - t2) / (t2 - t1);
        m++;
    }
    /* the three end in the same state, or a task ran wrongly */
    ok = ok && bench_rigid_engine.hash(a) == bench_rigid_engine.hash(b) &&
         bench_rigid_engine.hash(b) == bench_rigid_engine.hash(c);
    if (ok) {
        tasks_quartiles(rb, m, q_b);
        tasks_quartiles(rc, m, q_c);
        *most = tc.most;
    }
    free(rb);
    free(rc);
    if (a != NULL) bench_rigid_engine.destroy(a);
    if (b != NULL) bench_rigid_engine.destroy(b);
    if (c != NULL) bench_rigid_engine.destroy(c);
    return ok;
}

static int tasks_scene(const char *arg, int steps, const rg_task_system *pool)
{
    char name[32];
    const char *colon = strchr(arg, ':');
    size_t len = colon != NULL ? (size_t)(colon - arg) : strlen(arg);
    int n = colon != NULL ? atoi(colon + 1) : 10000;
    if (len == 0 || len >= sizeof name || n < 1) return 0;
    memcpy(name, arg, len);
    name[len] = 0;
    const bench_scene_def *d = bench_scene_find(name);
    bench_scene s;
    if (d == NULL || !bench_scene_build(&s, d, n)) {
        fprintf(stderr, "bench-tasks: no scene %s\n", arg);
        return 0;
    }
    if (s.drive != NULL) { /* driven step by step (the platformer): not a pile */
        fprintf(stderr, "bench-tasks: %s is driven by the bench's harness, not a scene for this tool\n", name);
        free(s.bodies);
        return 0;
    }
    s.sleep = 0;
    int32_t(*log)[TASKS_MAX][2] = calloc((size_t)steps, sizeof *log);
    int32_t *col = malloc((size_t)steps * sizeof *col);
    double qb[3], qc[3];
    int32_t most = 0;
    int ok = log != NULL && col != NULL;
    printf("== %s %d, sleeping off: %d steps in turns, medians (quartiles) of per-step ratios over the last %d\n",
           name, n, steps, steps - steps / 2);
    bench_cores_line(stdout, "before"); /* what moving data between the cores costs now */
    /* every task inline, then every task on the pool (and the tasks' order learnt) */
    ok = ok && tasks_race(&s, steps, pool, TASKS_ALL, -1, log, qb, qc, &most);
    if (ok) {
        printf("two workers, every task inline, over one worker:     %.3f (%.3f-%.3f)\n", qb[1], qb[0], qb[2]);
        printf("every task on the pool, over every task inline:      %.3f (%.3f-%.3f)\n", qc[1], qc[0], qc[2]);
        printf("so two workers over one, about:                      %.3f\n", qb[1] * qc[1]);
        printf("task  items  min_range  step with this task alone inline, over every task on the pool\n");
    }
    int gain = 0, lose = 0, tasks = most < TASKS_MAX ? most : TASKS_MAX;
    for (int32_t k = 0; k < tasks && ok; k++) {
        /* the task's items (median over the last half) and min_range ('*' when it varies) */
        int32_t m = 0, least = -1, same = 1;
        for (int r = steps / 2; r < steps; r++) {
            if (log[r][k][1] == 0) continue; /* no k-th task that step */
            col[m++] = log[r][k][0];
            if (least >= 0 && log[r][k][1] != least) same = 0;
            least = log[r][k][1];
        }
        if (m == 0) continue;
        qsort(col, (size_t)m, sizeof *col, tasks_cmp_i32);
        int32_t most_k = 0;
        ok = tasks_race(&s, steps, pool, -1, k, NULL, qb, qc, &most_k);
        if (!ok) break;
        /* inline faster: the pool loses on this task */
        const char *verdict = qc[2] < 1 ? "  loses" : qc[0] > 1 ? "  gains" : "";
        lose += qc[2] < 1;
        gain += qc[0] > 1;
        char mr[16];
        if (same)
            snprintf(mr, sizeof mr, "%d", (int)least);
        else
            snprintf(mr, sizeof mr, "*");
        printf("%4d %6d %10s  %.3f (%.3f-%.3f)%s%s\n", (int)k, (int)col[m / 2], mr, qc[1], qc[0], qc[2], verdict,
               m < steps - steps / 2 ? "  (not in every step)" : "");
    }
    if (ok)
        printf("%d tasks: on the pool, %d gain and %d lose (the quartiles of the step with the task inline clear of 1)\n",
               tasks, gain, lose);
    else
        printf("bench-tasks: %s %d failed (a world not made, or the worlds' states differed)\n", name, n);
    bench_cores_line(stdout, "after");
    free(log);
    free(col);
    free(s.bodies);
    return ok;
}

int main(int argc, char **argv)
{
    const char *scenes[16];
    int ns = 0, steps = 400;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
            steps = atoi(argv[++i]);
        } else if (argv[i][0] != '-' && ns < 16) {
            scenes[ns++] = argv[i];
        } else {
            fprintf(stderr, "usage: bench-tasks [SCENE:N ...] [--steps S]\n");
            return 2;
        }
    }
    if (steps < 8 || steps > TASKS_STEPS) {
        fprintf(stderr, "bench-tasks: --steps in [8, %d]\n", TASKS_STEPS);
        return 2;
    }
    if (ns == 0) {
        scenes[ns++] = "boxes:10000";
        scenes[ns++] = "rain:10000";
    }
    rg_thread_pool *pool;
    rg_task_system sys;
    if (rg_thread_pool_create(2, &pool) != RG_OK || rg_thread_pool_task_system(pool, &sys) != RG_OK) {
        fprintf(stderr, "bench-tasks: no pool of two threads\n");
        return 1;
    }
    int failed = 0;
    for (int i = 0; i < ns; i++) failed |= !tasks_scene(scenes[i], steps, &sys);
    rg_thread_pool_destroy(pool);
    return failed;
}
