/* bench_run.c: the harness's runs (bench_run.h): a scene on an entrant, step by step timed,
 * R runs per scene with the entrants interleaved, their medians and quality combined into
 * one result, and a result found again by scene, size, sleep and label.  bench.c parses
 * the options and reports; bench_sweep.c runs the settings of the quality-against-cost
 * chart through here. */
#define _GNU_SOURCE 1 /* clock_gettime, mallinfo2 */
#include <malloc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_run.h"

/* ---------------------------------------------------------------- timing and statistics */

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median and nearest-rank percentile of v[0..n) (sorts v). */
static double quantile(double *v, int32_t n, double q)
{
    if (n <= 0) return (double)NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    if (q == 0.5) return (n & 1) ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
    int32_t k = (int32_t)ceil(q * n) - 1;
    if (k < 0) k = 0;
    if (k >= n) k = n - 1;
    return v[k];
}

static size_t heap_in_use(void)
{
    struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
}

/* Median over the runs of each run's median (mean: 0) or mean (1) of its first k steps. */
static double prefix_stat(const bench_run *runs, int32_t nruns, int32_t k, int mean)
{
    double per[64], *tmp = malloc((size_t)(k > 0 ? k : 1) * sizeof *tmp);
    int32_t m = 0;
    if (tmp == NULL) return (double)NAN;
    for (int32_t i = 0; i < nruns && m < 64; i++) {
        if (!runs[i].ok || runs[i].steps < k) continue;
        double sum = 0;
        for (int32_t j = 0; j < k; j++) sum += tmp[j] = runs[i].times[j];
        per[m++] = mean ? sum / k : quantile(tmp, k, 0.5);
    }
    free(tmp);
    return quantile(per, m, 0.5);
}

/* ---------------------------------------------------------------- one run */

typedef struct state_buf {
    float *x, *y, *vx, *vy;
} state_buf;

typedef struct push_ctx {
    const bench_engine *e;
    void *ctx;
} push_ctx;

static void push_force(void *ctx, int32_t k, double fx, double fy)
{
    push_ctx *p = ctx;
    p->e->force(p->ctx, k, fx, fy);
}

static void push_impulse(void *ctx, int32_t k, double ix, double iy)
{
    push_ctx *p = ctx;
    p->e->impulse(p->ctx, k, ix, iy);
}

static bench_run run_once(const bench_entrant *who, const bench_scene *s0, const bench_scene_def *d,
                          const bench_options *o, state_buf *st)
{
    const bench_engine *e = who->engine;
    bench_scene s = *s0;
    bench_run r;
    memset(&r, 0, sizeof r);
    s.workers = who->workers;
    r.times = malloc((size_t)o->steps * sizeof *r.times);
    if (r.times == NULL) return r;
    size_t heap0 = heap_in_use();
    void *ctx = e->create(&s);
    if (ctx == NULL) return r;
    push_ctx pc = { e, ctx };
    bench_pusher pusher = { &pc, push_force, push_impulse };
    double last_moving = 0, spent = 0; /* time of the last sample with a shaped body moving */
    double deepest = -1;               /* deepest overlap over the samples */
    int64_t calls_half = 0;
    r.steady_allocs = -1;
    int32_t i = 0;
    while (i < o->steps) {
        if (i == o->steps / 2 && e->alloc_calls != NULL) calls_half = e->alloc_calls(ctx);
        double t0 = now_ms();
        if (s.drive != NULL) s.drive(&s, i, &pusher);
        e->step(ctx, BENCH_DT);
        spent += r.times[i] = now_ms() - t0;
        if (e->contacts != NULL) {
            bench_contacts c;
            e->contacts(ctx, &c);
            r.contacts.touching += c.touching;
            r.contacts.one_way += c.one_way;
            r.contacts.pre_solve_calls += c.pre_solve_calls;
        }
        i++;
        if (d->settles && i % BENCH_SAMPLE_EVERY == 0) {
            e->read(ctx, st->x, st->y, st->vx, st->vy);
            if (bench_max_speed(&s, st->vx, st->vy, 1) >= BENCH_REST_SPEED) last_moving = i * BENCH_DT;
            double now = bench_deepest_overlap(&s, st->x, st->y);
            if (!(now <= deepest)) deepest = now;
        }
        if (spent > o->budget_s * 1e3) break;
    }
    r.steps = i;
    r.contacts.touching /= i;
    r.contacts.one_way /= i;
    r.contacts.pre_solve_calls /= i;
    e->read(ctx, st->x, st->y, st->vx, st->vy);
    if (o->dump != NULL)
        for (int32_t k = 0; k < s.ndynamic; k++)
            fprintf(o->dump, "%s,%d,%s,%d,%.6g,%.6g,%.6g,%.6g\n", s.name, (int)s.size, who->label, (int)k,
                    (double)st->x[k], (double)st->y[k], (double)st->vx[k], (double)st->vy[k]);
    if (e->alloc_calls != NULL && r.steps == o->steps) r.steady_allocs = e->alloc_calls(ctx) - calls_half;
    size_t peak = 0, own = e->bytes(ctx, &peak);
    r.peak = peak;
    size_t heap1 = heap_in_use();
    r.bytes = own > 0 ? own : (heap1 > heap0 ? heap1 - heap0 : 0);
    bench_quality_measure(&s, st->x, st->y, st->vx, st->vy, &r.q);
    if (e->hash != NULL) r.hash = e->hash(ctx);
    r.q.rest = (double)NAN;
    if (d->settles) {
        double end = r.q.overlap > r.q.wall ? r.q.overlap : r.q.wall;
        r.q.peak = deepest > end ? deepest : end;
        int32_t last_sample = r.steps / BENCH_SAMPLE_EVERY * BENCH_SAMPLE_EVERY; /* moving then: never */
        r.q.rest = last_moving >= last_sample * BENCH_DT - 1e-9 ? -1 : last_moving;
    }
    e->destroy(ctx);
    r.mean = spent / r.steps;
    int32_t until = r.steps;
    if (d->settles && r.q.rest > 0) until = (int32_t)(r.q.rest / BENCH_DT + 0.5);
    if (until < 1) until = 1;
    if (until > r.steps) until = r.steps;
    double head = 0;
    for (int32_t k = 0; k < until; k++) head += r.times[k];
    r.settling = head / until;
    double *sorted = malloc((size_t)r.steps * sizeof *sorted);
    if (sorted == NULL) return r;
    memcpy(sorted, r.times, (size_t)r.steps * sizeof *sorted);
    r.median = quantile(sorted, r.steps, 0.5);
    r.p95 = quantile(sorted, r.steps, 0.95);
    free(sorted);
    r.ok = 1;
    return r;
}

/* ---------------------------------------------------------------- a scene's figures */

static void combine(bench_result *res, const bench_run *runs, int32_t nruns)
{
    double med[64], mean[64], p95[64], settle[64], touching[64], one_way[64], calls[64];
    int32_t k = 0;
    res->steps = res->steps_asked;
    for (int32_t i = 0; i < nruns && k < 64; i++) {
        if (!runs[i].ok) continue;
        med[k] = runs[i].median;
        mean[k] = runs[i].mean;
        p95[k] = runs[i].p95;
        settle[k] = runs[i].settling;
        touching[k] = runs[i].contacts.touching;
        one_way[k] = runs[i].contacts.one_way;
        calls[k] = runs[i].contacts.pre_solve_calls;
        res->q = runs[i].q;
        res->bytes_body = (double)runs[i].bytes / (res->nbodies > 0 ? res->nbodies : 1);
        res->peak_body = (double)runs[i].peak / (res->nbodies > 0 ? res->nbodies : 1);
        if (runs[i].steps < res->steps) res->steps = runs[i].steps;
        if (k > 0 && runs[i].hash != res->hash) res->hash_varies = 1;
        res->hash = runs[i].hash;
        k++;
    }
    res->steady_allocs = -1;
    for (int32_t i = 0; i < nruns; i++)
        if (runs[i].ok && runs[i].steady_allocs > res->steady_allocs) res->steady_allocs = runs[i].steady_allocs;
    res->ok = k > 0;
    res->runs = k;
    if (k == 0) return;
    res->median = quantile(med, k, 0.5);
    res->min_median = med[0];
    res->max_median = med[k - 1];
    res->mean = quantile(mean, k, 0.5);
    res->p95 = quantile(p95, k, 0.5);
    res->settling = quantile(settle, k, 0.5);
    res->contacts.touching = quantile(touching, k, 0.5);
    res->contacts.one_way = quantile(one_way, k, 0.5);
    res->contacts.pre_solve_calls = quantile(calls, k, 0.5);
    res->ns_body = res->median * 1e6 / (res->ndynamic > 0 ? res->ndynamic : 1);
}

/* The rigid entrant a result is compared with: as many workers, else one. */
static int reference_of(const bench_entrant *const *who, int nwho, int e)
{
    int one = -1;
    for (int k = 0; k < nwho; k++) {
        if (who[k]->engine != &bench_rigid_engine) continue;
        if (who[k]->workers == who[e]->workers) return k;
        if (who[k]->workers == 1 && one < 0) one = k;
    }
    return one;
}

int bench_run_scene(const bench_scene *s, const bench_scene_def *d, const bench_entrant *const *who,
                    int nwho, const bench_options *opts, bench_result *out)
{
    int32_t reps = opts->repeats;
    bench_run *runs = calloc((size_t)reps * (size_t)nwho, sizeof *runs);
    state_buf st;
    size_t nd = (size_t)(s->ndynamic > 0 ? s->ndynamic : 1);
    st.x = malloc(4 * nd * sizeof(float));
    if (runs == NULL || st.x == NULL) {
        free(runs);
        free(st.x);
        return 0;
    }
    st.y = st.x + nd;
    st.vx = st.y + nd;
    st.vy = st.vx + nd;
    for (int32_t rep = 0; rep < reps; rep++)
        for (int e = 0; e < nwho; e++) runs[e * reps + rep] = run_once(who[e], s, d, opts, &st);
    for (int e = 0; e < nwho; e++) {
        bench_result *r = &out[e];
        memset(r, 0, sizeof *r);
        r->def = d;
        snprintf(r->scene, sizeof r->scene, "%s", s->name);
        r->n = s->size;
        r->sleep = s->sleep;
        r->who = who[e];
        r->nbodies = s->nbodies;
        r->ndynamic = s->ndynamic;
        r->steps_asked = opts->steps;
        r->solver_set = s->solver_set;
        r->solver[0] = s->solver[0];
        r->solver[1] = s->solver[1];
        combine(r, &runs[e * reps], reps);
        r->has_hash = r->ok && who[e]->engine->hash != NULL;
    }
    for (int e = 0; e < nwho; e++) {
        bench_result *r = &out[e];
        int ref = reference_of(who, nwho, e);
        r->ref_median = r->ref_mean = (double)NAN;
        if (!r->ok || ref < 0 || !out[ref].ok) continue;
        r->ref = who[ref];
        int32_t k = r->steps < out[ref].steps ? r->steps : out[ref].steps;
        if (k == opts->steps) {
            r->ref_median = out[ref].median;
            r->ref_mean = out[ref].mean;
        } else { /* both over the steps both did */
            r->ref_median = prefix_stat(&runs[ref * reps], reps, k, 0);
            r->ref_mean = prefix_stat(&runs[ref * reps], reps, k, 1);
            if (r->steps > k) {
                r->median = prefix_stat(&runs[e * reps], reps, k, 0);
                r->mean = prefix_stat(&runs[e * reps], reps, k, 1);
            }
        }
    }
    for (int32_t i = 0; i < reps * nwho; i++) free(runs[i].times);
    free(runs);
    free(st.x);
    return 1;
}

const bench_result *bench_find(const bench_result *rs, int32_t nr, const char *scene, int32_t n,
                               int32_t sleep, const char *label)
{
    for (int32_t i = 0; i < nr; i++)
        if (rs[i].ok && strcmp(rs[i].scene, scene) == 0 && (n == 0 || rs[i].n == n) &&
            (sleep < 0 || rs[i].sleep == sleep) && strcmp(rs[i].who->label, label) == 0)
            return &rs[i];
    return NULL;
}
