/* bench_gameplay.c: the benchmark's scenes for rigid's gameplay collision, and their report.
 *
 * A variant is a plain scene (rain, boxes, platformer) with sleeping off, so that every pair
 * is solved every step and a pile's median step is its settled steady state: as it is
 * (BENCH_AWAKE, the reference), with every static box one-way, or with a pre-solve hook
 * that keeps every pair, or under Verlet or RK4 (what those integrators cost in contact: their
 * own stages, and the narrowphase's scalar path, which checks both motions; their bodies
 * settle a little otherwise, so the piles are alike, not the same).  A pile's floor and
 * walls then face the pile, so its bodies, which
 * only ever press against those faces, move exactly as in the reference, and the difference
 * in time per step is the cost of the feature; the platformer's tiles face up, so its
 * walkers jump up through the platforms instead of bumping into them.  The report divides
 * that difference by the pairs it concerns (pairs with a one-way shape, or the hook's calls,
 * per step) and gives the range the runs allow (slowest against fastest run). */
#include <stdio.h>
#include <string.h>

#include "bench.h"

void bench_gameplay_variant(bench_scene *s, int32_t variant)
{
    s->variant = variant;
    if (variant != BENCH_ONE_WAY) return;
    for (int32_t i = 0; i < s->nbodies; i++) {
        bench_body *b = &s->bodies[i];
        if (b->type != BENCH_STATIC || b->shape != BENCH_SHAPE_BOX || b->sensor) continue;
        int wall = b->b > b->a;
        b->nx = wall ? (b->x < 0 ? 1.0 : -1.0) : 0.0;
        b->ny = wall ? 0.0 : 1.0;
    }
}

static const bench_gameplay_row *reference_of(const bench_gameplay_row *rows, int32_t nrows,
                                              const bench_gameplay_row *v)
{
    for (int32_t i = 0; i < nrows; i++)
        if (rows[i].variant == BENCH_AWAKE && rows[i].n == v->n && strcmp(rows[i].base, v->base) == 0)
            return &rows[i];
    return NULL;
}

static void print_row(const bench_gameplay_row *q, const bench_gameplay_row *ref)
{
    double c = q->per_step.touching;
    char extra[3][32] = { "", "", "" };
    if (ref != NULL) {
        double d = q->ms - ref->ms, lo = q->ms_lo - ref->ms_hi, hi = q->ms_hi - ref->ms_lo;
        double concerned = q->variant == BENCH_ONE_WAY ? q->per_step.one_way : q->per_step.pre_solve_calls;
        snprintf(extra[0], sizeof extra[0], "%+.4f", d);
        if (c > 0) snprintf(extra[1], sizeof extra[1], "%+.2f", d * 1e6 / c);
        if (concerned > 0)
            snprintf(extra[2], sizeof extra[2], "%+.2f (%+.1f..%+.1f)", d * 1e6 / concerned,
                     lo * 1e6 / concerned, hi * 1e6 / concerned);
    }
    printf("%-20s %7d %8.4f %9.1f %9.1f %9.1f %8.2f %9s %8s %22s\n", q->scene, (int)q->n, q->ms, c,
           q->per_step.one_way, q->per_step.pre_solve_calls, c > 0 ? q->ms * 1e6 / c : 0.0, extra[0],
           extra[1], extra[2]);
}

void bench_gameplay_report(const bench_gameplay_row *rows, int32_t nrows)
{
    int any = 0;
    for (int32_t i = 0; i < nrows; i++) {
        const bench_gameplay_row *ref = &rows[i];
        if (ref->variant != BENCH_AWAKE) continue;
        if (!any) {
            printf("\ngameplay collision (rigid): what one-way shapes, a pre-solve hook and the Verlet and RK4\n"
                   "integrators cost per pair.\n"
                   "Sleeping off; median ms per step (medians over the runs); per step, means over all "
                   "steps: touching pairs,\npairs with a one-way shape, pre-solve calls.  extra: the "
                   "variant less the -awake scene, per step, per touching pair,\nand per pair "
                   "concerned (one-way pair or hook call), with the range the runs allow.\n");
            printf("%-20s %7s %8s %9s %9s %9s %8s %9s %8s %22s\n", "scene", "N", "ms/step",
                   "contacts", "one-way", "calls", "ns/pair", "extra ms", "extra ns", "extra ns");
            printf("%-20s %7s %8s %9s %9s %9s %8s %9s %8s %22s\n", "", "", "", "/step", "/step",
                   "/step", "-step", "/step", "/pair", "per pair concerned");
            any = 1;
        }
        print_row(ref, NULL);
        for (int32_t j = 0; j < nrows; j++)
            if (rows[j].variant > BENCH_AWAKE && reference_of(rows, nrows, &rows[j]) == ref)
                print_row(&rows[j], ref);
    }
}
