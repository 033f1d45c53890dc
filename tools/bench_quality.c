/* bench_quality.c: the quality of a run, measured by one piece of code for every engine from
 * the state each hands back: the deepest and the mean overlap, the largest speed at the end,
 * and the bodies that left the container. */
#include <math.h>
#include <stdlib.h>

#include "bench.h"

/* Overlap depth of two shapes (negative when apart). */
static double shape_overlap(int sa, double xa, double ya, double aa, double ba,
                            int sb, double xb, double yb, double ab, double bb)
{
    if (sa == BENCH_SHAPE_BOX && sb == BENCH_SHAPE_CIRCLE)
        return shape_overlap(sb, xb, yb, ab, bb, sa, xa, ya, aa, ba);
    double dx = xb - xa, dy = yb - ya;
    if (sa == BENCH_SHAPE_CIRCLE && sb == BENCH_SHAPE_CIRCLE) return aa + ab - sqrt(dx * dx + dy * dy);
    if (sa == BENCH_SHAPE_BOX) { /* box-box */
        double ox = aa + ab - fabs(dx), oy = ba + bb - fabs(dy);
        return ox < oy ? ox : oy;
    }
    /* circle a against box b */
    double px = fabs(dx), py = fabs(dy); /* circle centre relative to box, folded */
    if (px <= ab && py <= bb) {          /* centre inside: distance to leave + radius */
        double ex = ab - px, ey = bb - py;
        return aa + (ex < ey ? ex : ey);
    }
    double qx = px > ab ? px - ab : 0, qy = py > bb ? py - bb : 0;
    return aa - sqrt(qx * qx + qy * qy);
}

typedef struct qitem {
    double x, y, a, b;
    int32_t shape, dynamic;
} qitem;

static uint32_t cell_hash(int64_t cx, int64_t cy)
{
    uint64_t h = (uint64_t)cx * 0x9E3779B97F4A7C15ull ^ (uint64_t)cy * 0xC2B2AE3D27D4EB4Full;
    return (uint32_t)(h >> 32);
}

/* Running deepest and mean overlap. */
typedef struct overlap_sum {
    double sum;
    int64_t count;
} overlap_sum;

static void overlap_add(overlap_sum *m, double *deepest, double o)
{
    if (o > *deepest) *deepest = o;
    if (o > 0) {
        m->sum += o;
        m->count++;
    }
}

/* Deepest overlaps and the mean over the overlapping pairs, over a hash grid of the small
 * shapes; shapes larger than a cell (container walls) are checked against every moving
 * body. */
static void measure_overlaps(const bench_scene *s, const float *x, const float *y, bench_quality *q)
{
    int32_t n = s->nbodies, ni = 0, nbig = 0, nstatic = 0;
    overlap_sum mean = { 0, 0 };
    qitem *it = malloc((size_t)n * sizeof *it);
    int32_t *big = malloc((size_t)n * sizeof *big);
    double maxhalf = 0;
    q->overlap = -(double)INFINITY;
    q->wall = -(double)INFINITY;
    if (it == NULL || big == NULL) goto done;
    int32_t k = 0;
    for (int32_t i = 0; i < n; i++) {
        const bench_body *bb = &s->bodies[i];
        int dyn = bb->type == BENCH_DYNAMIC;
        int32_t kk = dyn ? k++ : -1;
        if (bb->shape == BENCH_SHAPE_NONE || bb->sensor) continue;
        qitem *e = &it[ni];
        e->x = dyn ? (double)x[kk] : bb->x;
        e->y = dyn ? (double)y[kk] : bb->y;
        e->a = bb->a;
        e->b = bb->shape == BENCH_SHAPE_CIRCLE ? bb->a : bb->b;
        e->shape = bb->shape;
        e->dynamic = dyn;
        nstatic += !dyn;
        if (e->a > 1.0 || e->b > 1.0) {
            big[nbig++] = ni;
        } else {
            if (e->a > maxhalf) maxhalf = e->a;
            if (e->b > maxhalf) maxhalf = e->b;
        }
        ni++;
    }
    for (int32_t i = 0; i < ni; i++) { /* big statics against every moving body */
        if (!it[i].dynamic) continue;
        for (int32_t j = 0; j < nbig; j++) {
            const qitem *a = &it[i], *b = &it[big[j]];
            double o = shape_overlap(a->shape, a->x, a->y, a->a, a->b, b->shape, b->x, b->y, b->a, b->b);
            overlap_add(&mean, &q->wall, o);
        }
    }
    double cell = 2 * maxhalf > 0 ? 2 * maxhalf : 1;
    uint32_t size = 1;
    while (size < 2u * (uint32_t)ni) size <<= 1;
    int32_t *head = malloc((size_t)size * sizeof *head), *next = malloc((size_t)ni * sizeof *next);
    if (head == NULL || next == NULL) {
        free(head);
        free(next);
        goto done;
    }
    for (uint32_t i = 0; i < size; i++) head[i] = -1;
    for (int32_t i = 0; i < ni; i++) {
        if (it[i].a > 1.0 || it[i].b > 1.0) continue;
        uint32_t h = cell_hash((int64_t)floor(it[i].x / cell), (int64_t)floor(it[i].y / cell)) & (size - 1);
        next[i] = head[h];
        head[h] = i;
    }
    for (int32_t i = 0; i < ni; i++) {
        const qitem *a = &it[i];
        if (!a->dynamic || a->a > 1.0 || a->b > 1.0) continue;
        int64_t cx = (int64_t)floor(a->x / cell), cy = (int64_t)floor(a->y / cell);
        for (int64_t dy = -1; dy <= 1; dy++)
            for (int64_t dx = -1; dx <= 1; dx++)
                for (int32_t j = head[cell_hash(cx + dx, cy + dy) & (size - 1)]; j >= 0; j = next[j]) {
                    const qitem *b = &it[j];
                    if (j == i || (b->dynamic && j < i)) continue;
                    double o = shape_overlap(a->shape, a->x, a->y, a->a, a->b, b->shape, b->x, b->y, b->a, b->b);
                    overlap_add(&mean, b->dynamic ? &q->overlap : &q->wall, o);
                }
    }
    free(head);
    free(next);
done:
    /* Apart is no overlap (and no static shape at all stays -inf: "none"). */
    if (q->overlap < 0) q->overlap = 0;
    if (q->wall < 0 && nstatic > 0) q->wall = 0;
    q->mean_overlap = mean.count > 0 ? mean.sum / (double)mean.count : 0;
    free(it);
    free(big);
}

double bench_max_speed(const bench_scene *s, const float *vx, const float *vy, int shaped_only)
{
    double m = 0;
    int32_t k = 0;
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body *bb = &s->bodies[i];
        if (bb->type != BENCH_DYNAMIC) continue;
        if (!shaped_only || bb->shape != BENCH_SHAPE_NONE) {
            double vxk = (double)vx[k], vyk = (double)vy[k];
            double v = sqrt(vxk * vxk + vyk * vyk);
            if (v > m || v != v) m = v;
        }
        k++;
    }
    return m;
}

static int32_t count_lost(const bench_scene *s, const float *x, const float *y)
{
    if (!s->has_container) return 0;
    int32_t lost = 0, k = 0;
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body *bb = &s->bodies[i];
        if (bb->type != BENCH_DYNAMIC) continue;
        if (bb->shape != BENCH_SHAPE_NONE &&
            (!(y[k] > -0.5f) || !(fabs((double)x[k]) < s->half_width + 0.5)))
            lost++;
        k++;
    }
    return lost;
}

void bench_quality_measure(const bench_scene *s, const float *x, const float *y, const float *vx,
                           const float *vy, bench_quality *q)
{
    q->vmax = bench_max_speed(s, vx, vy, 0);
    q->overlap = q->wall = q->mean_overlap = q->peak = (double)NAN;
    int shaped = 0;
    for (int32_t i = 0; i < s->nbodies && !shaped; i++) shaped = s->bodies[i].shape != BENCH_SHAPE_NONE;
    if (shaped) measure_overlaps(s, x, y, q);
    q->lost = count_lost(s, x, y);
}

double bench_deepest_overlap(const bench_scene *s, const float *x, const float *y)
{
    bench_quality q;
    measure_overlaps(s, x, y, &q);
    return q.overlap > q.wall ? q.overlap : q.wall;
}
