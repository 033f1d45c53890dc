/* bench_sweep.c: quality against cost (bench --sweep).  Each engine runs the scenes at
 * several solver settings along curves (rigid: velocity iterations 1-16 at 3 position
 * iterations, and position iterations 0-8 at 8 velocity; Box2D v3: substeps 1-8; Box2D 2.4:
 * velocity iterations at 3 position, position at 8 velocity; Chipmunk: iterations), each
 * setting twice: sleeping off for the time per step (median) and the pile's overlaps (the
 * deepest and the mean at the end, the deepest over the run), sleeping on for the time a
 * game pays (mean) and the time to rest.  Every row gets
 * the Pareto flags of its scene: on the front when no other setting of any engine is at
 * least as cheap and at least as good, and better in one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_run.h"

typedef struct sweep_curve {
    const char *engine;   /* engine name; "b2v3" is the v3 build the sweep runs */
    const char *label;
    int vary;             /* 0: a takes the values, 1: b does */
    int32_t fixed;        /* the other one */
    int32_t values[12];
    int32_t nvalues;
    int32_t def_a, def_b; /* the engine's default */
} sweep_curve;

static const sweep_curve CURVES[] = {
    { "rigid", "rigid: velocity iterations (3 position)", 0, 3, { 1, 2, 3, 4, 6, 8, 10, 12, 16 }, 9, 8, 3 },
    { "rigid", "rigid: position iterations (8 velocity)", 1, 8, { 0, 1, 2, 3, 4, 6, 8 }, 7, 8, 3 },
    { "b2v3", "Box2D v3: substeps", 0, 0, { 1, 2, 3, 4, 5, 6, 7, 8 }, 8, 4, 0 },
    { "box2d", "Box2D 2.4: velocity iterations (3 position)", 0, 3, { 1, 2, 4, 8, 16 }, 5, 8, 3 },
    { "box2d", "Box2D 2.4: position iterations (8 velocity)", 1, 8, { 1, 3, 8 }, 3, 8, 3 },
    { "chipmunk", "Chipmunk 7: iterations", 0, 0, { 1, 2, 4, 6, 10, 20, 40 }, 7, 10, 0 },
};
#define NCURVES ((int)(sizeof CURVES / sizeof CURVES[0]))

typedef struct sweep_row {
    const char *scene;
    int32_t n;
    const bench_entrant *who;
    const char *curve;
    int32_t a, b, is_default;
    double median, max_overlap, peak, mean_overlap, sleep_mean, rest, rest_plot;
    int front[4];
    int copy;   /* the same run as an earlier row, on another curve */
} sweep_row;

/* a <= b in both and better in one: a dominates b. */
static int dominates(double ca, double qa, double cb, double qb)
{
    return ca <= cb && qa <= qb && (ca < cb || qa < qb);
}

/* The measures a front is drawn for: 0 deepest at the end, 1 deepest over the run, 2 mean
 * at the end (against the median, sleeping off), 3 the time to rest (against the mean,
 * sleeping on). */
#define NMEASURES 4
static void measure_of(const sweep_row *r, int m, double *cost, double *q)
{
    *cost = m < 3 ? r->median : r->sleep_mean;
    *q = m == 0 ? r->max_overlap : m == 1 ? r->peak : m == 2 ? r->mean_overlap : r->rest_plot;
}

static void fronts(sweep_row *rows, int32_t n)
{
    for (int32_t i = 0; i < n; i++)
        for (int m = 0; m < NMEASURES; m++) {
            double ci, qi, cj, qj;
            measure_of(&rows[i], m, &ci, &qi);
            int on = 1;
            for (int32_t j = 0; j < n && on; j++) {
                if (j == i || strcmp(rows[j].scene, rows[i].scene) != 0 || rows[j].n != rows[i].n) continue;
                measure_of(&rows[j], m, &cj, &qj);
                if (dominates(cj, qj, ci, qi)) on = 0;
            }
            rows[i].front[m] = on;
        }
}

/* The entrant a curve runs on: one worker, the engine named (for v3 the AVX2 build when
 * there, else SSE2). */
static const bench_entrant *curve_entrant(const sweep_curve *c, const bench_entrant *who, int nwho)
{
    const bench_entrant *pick = NULL;
    for (int e = 0; e < nwho; e++) {
        if (who[e].workers != 1) continue;
        const char *name = who[e].engine->name;
        if (strcmp(c->engine, "b2v3") == 0 ? strncmp(name, "b2v3", 4) == 0 : strcmp(name, c->engine) == 0)
            if (pick == NULL || strcmp(name, "b2v3-avx2") == 0) pick = &who[e];
    }
    return pick;
}

static void print_row(const sweep_row *r)
{
    char rest[16];
    if (r->rest < 0) snprintf(rest, sizeof rest, "never");
    else snprintf(rest, sizeof rest, "%.2f", r->rest);
    printf("%-6s %6d %-10s %3d %3d %-3s %9.3f %9.3f %9.3f %9.3f %9.3f %7s  %s\n", r->scene, (int)r->n,
           r->who->label, (int)r->a, (int)r->b, r->is_default ? "def" : "", r->median, 1e3 * r->max_overlap,
           1e3 * r->peak, 1e3 * r->mean_overlap, r->sleep_mean, rest, r->curve);
    fflush(stdout);
}

int bench_sweep(const bench_job *jobs, int njobs, const bench_entrant *who, int nwho,
                const bench_options *opts, const char *csv)
{
    int32_t cap = njobs * 64, nrows = 0;
    sweep_row *rows = calloc((size_t)cap, sizeof *rows);
    if (rows == NULL) return 0;
    printf("quality against cost: each engine at several solver settings (a, b: rigid and Box2D 2.4 "
           "velocity, position iterations; v3 substeps; Chipmunk iterations)\n"
           "median: ms per step, sleeping off; overlaps, sleeping off, in mm: the deepest at the end "
           "(bodies or walls), the deepest over the run (every %d steps), the mean over the pairs "
           "overlapping at the end; sleeping on: mean ms per step and the time to rest\n"
           "%-6s %6s %-10s %3s %3s %-3s %9s %9s %9s %9s %9s %7s  %s\n", BENCH_SAMPLE_EVERY, "scene", "N",
           "engine", "a", "b", "", "median", "deepest", "peak", "mean", "sleep on", "rest", "curve");
    for (int j = 0; j < njobs; j++) {
        bench_scene s;
        if (!jobs[j].def->settles || !bench_scene_build(&s, jobs[j].def, jobs[j].n)) {
            fprintf(stderr, "bench: --sweep runs the piles (rain, boxes)\n");
            free(rows);
            return 0;
        }
        for (int c = 0; c < NCURVES; c++) {
            const sweep_curve *cv = &CURVES[c];
            const bench_entrant *e = curve_entrant(cv, who, nwho);
            if (e == NULL) continue;
            for (int32_t v = 0; v < cv->nvalues && nrows < cap; v++) {
                int32_t a = cv->vary == 0 ? cv->values[v] : cv->fixed;
                int32_t b = cv->vary == 1 ? cv->values[v] : cv->fixed;
                int32_t seen = -1; /* a setting two curves share runs once */
                for (int32_t k = 0; k < nrows && seen < 0; k++)
                    if (rows[k].who == e && rows[k].a == a && rows[k].b == b && rows[k].n == s.size &&
                        strcmp(rows[k].scene, s.name) == 0)
                        seen = k;
                if (seen >= 0) {
                    rows[nrows] = rows[seen];
                    rows[nrows].curve = cv->label;
                    rows[nrows++].copy = 1;
                    continue;
                }
                bench_result res[2];
                s.solver_set = 1;
                s.solver[0] = a;
                s.solver[1] = b;
                for (int sl = 0; sl < 2; sl++) {
                    s.sleep = sl;
                    if (!bench_run_scene(&s, jobs[j].def, &e, 1, opts, &res[sl])) {
                        free(rows);
                        return 0;
                    }
                }
                if (!res[0].ok || !res[1].ok) continue;
                sweep_row *r = &rows[nrows++];
                r->scene = jobs[j].def->name;
                r->n = s.size;
                r->who = e;
                r->curve = cv->label;
                r->a = a;
                r->b = b;
                r->is_default = a == cv->def_a && b == cv->def_b;
                r->median = res[0].median;
                r->max_overlap = res[0].q.overlap > res[0].q.wall ? res[0].q.overlap : res[0].q.wall;
                r->peak = res[0].q.peak;
                r->mean_overlap = res[0].q.mean_overlap;
                r->sleep_mean = res[1].mean;
                r->rest = res[1].q.rest;
                r->rest_plot = r->rest >= 0 ? r->rest : res[1].steps * BENCH_DT; /* never: all */
                print_row(r);
            }
        }
        free(s.bodies);
    }
    fronts(rows, nrows);
    printf("\nPareto fronts (no other setting of any engine at least as cheap and as good):\n");
    for (int m = 0; m < NMEASURES; m++) {
        static const char *const what[NMEASURES] = { "median vs deepest overlap at the end",
                                                     "median vs deepest overlap over the run",
                                                     "median vs mean overlap at the end",
                                                     "sleeping-on mean vs time to rest" };
        printf("  %s:", what[m]);
        for (int32_t i = 0; i < nrows; i++)
            if (rows[i].front[m] && !rows[i].copy)
                printf(" %s %d %s(%d,%d)%s;", rows[i].scene, (int)rows[i].n, rows[i].who->label,
                       (int)rows[i].a, (int)rows[i].b, rows[i].is_default ? " default" : "");
        printf("\n");
    }
    if (csv != NULL) {
        FILE *f = fopen(csv, "w");
        if (f == NULL) {
            perror(csv);
            free(rows);
            return 0;
        }
        fprintf(f, "scene,n,engine,curve,a,b,default,median_ms,max_overlap_m,peak_overlap_m,mean_overlap_m,"
                   "sleep_mean_ms,rest_s,rest_plot_s,front_max,front_peak,front_mean,front_rest\n");
        for (int32_t i = 0; i < nrows; i++) {
            const sweep_row *r = &rows[i];
            fprintf(f, "%s,%d,%s,%s,%d,%d,%d,%.6f,%.6g,%.6g,%.6g,%.6f,%.4g,%.4g,%d,%d,%d,%d\n", r->scene,
                    (int)r->n, r->who->label, r->curve, (int)r->a, (int)r->b, r->is_default, r->median,
                    r->max_overlap, r->peak, r->mean_overlap, r->sleep_mean, r->rest, r->rest_plot,
                    r->front[0], r->front[1], r->front[2], r->front[3]);
        }
        fclose(f);
    }
    free(rows);
    return 1;
}
