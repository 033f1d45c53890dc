/* continuous.c: timed impacts and the post-solve sweep (see continuous.h). */
#include <string.h>

#include "body.h"
#include "collision.h"
#include "contact.h"
#include "continuous.h"
#include "dispatch.h"
#include "solver.h"
#include "state.h"
#include "task.h"
#include "vec2.h"

/* Impacts of one body within this fraction of the step of each other count as one (a box
 * across a tile seam meets both tiles at once, to rounding). */
#define SAME_IMPACT RG_R(1e-4)

/* The fraction of the step at which movable body i (dense) meets what it meets, if it can be
 * timed, else 0.  It can when its solved rows are impacts at one moment and rows with
 * immovable bodies that stay apart, with at most one of them with another movable body, an
 * impact (*partner: that body, else -1).  No body in contact with it, and no body near it
 * but that partner, then has a velocity that depends on the moment of its impact. */
static rg_real continuous_impact_time(const rg_world *w, int32_t i, int32_t n, int32_t *partner)
{
    const contact_store *cs = &w->coll.contacts;
    const body_store *b = &w->b;
    int32_t s = b->slot[i];
    rg_real t0 = RG_HUGE, t1 = 0;
    *partner = -1;
    for (int32_t id = b->chead[i] - 1; id >= 0; id = contact_next(&cs->c[id], s)) {
        const contact *c = &cs->c[id];
        if (!(c->flags & CT_SOLVE)) continue;
        int32_t j = body_dense(w, contact_other(c, s));
        int impact = c->toi > 0;
        if (c->toi >= 0) {
            if (!impact) return 0;
            t0 = rg_min(t0, c->toi);
            t1 = rg_max(t1, c->toi);
        }
        if (j < n && b->inv_mass[j] > 0) {
            if (!impact || *partner >= 0) return 0;
            *partner = j;
        }
    }
    return t0 <= t1 && t1 - t0 <= SAME_IMPACT ? t0 : 0;
}

/* Whether movable body i is timed, at *t: it can be, and so can the partner of its impact with
 * another movable body (whose only such row is that impact). */
static int continuous_timed_body(const rg_world *w, int32_t i, int32_t n, rg_real *t)
{
    int32_t p, q;
    *t = continuous_impact_time(w, i, n, &p);
    return *t > 0 && (p < 0 || continuous_impact_time(w, p, n, &q) > 0);
}

int continuous_time_impacts(rg_world *w, collide_step *x)
{
    collide_world *cw = &w->coll;
    resolve_state *rs = &cw->resolve;
    solver_rows *rows = &cw->rows;
    const body_store *b = &w->b;
    if (x->nimp == 0) return 0;
    /* the times of the bodies the rows meet, which alone the solve reads (solver_rows_few) */
    if (solver_rows_few(x->nc, x->ns)) {
        for (int32_t r = 0; r < x->nc; r++) rs->stoi[rows->stage[r].a] = rs->stoi[rows->stage[r].b] = 0;
    } else {
        memset(rs->stoi, 0, (size_t)(x->ns + 1) * sizeof *rs->stoi);
    }
    int any = 0;
    for (int32_t k = 0; k < x->nimp; k++) {
        solver_constraint *r = &rows->stage[rows->imp[k]];
        int32_t ia = r->a - 1, ib = r->b - 1; /* -1: the ground */
        rg_real ta = 0, tb = 0;
        if (r->ima > 0 && !continuous_timed_body(w, ia, x->n, &ta)) continue;
        if (r->imb > 0 && !continuous_timed_body(w, ib, x->n, &tb)) continue;
        rg_real v1n = 0;
        if (ib >= 0) v1n += b->vx[ib] * r->nx + b->vy[ib] * r->ny;
        if (ia >= 0) v1n -= b->vx[ia] * r->nx + b->vy[ia] * r->ny;
        const contact *c = &cw->contacts.c[r->cid];
        r->vmin = solver_vout(c->vn0, v1n, r->toi, c->e, &x->p);
        if (r->ima > 0) rs->stoi[r->a] = ta;
        if (r->imb > 0) rs->stoi[r->b] = tb;
        any = 1;
    }
    return any;
}

/* Whether body i blocks a hit whose normal (nx, ny) points from i toward the other: always,
 * unless it is one-way and the normal is not on its side. */
static inline int continuous_one_way_blocks(const body_store *b, int32_t i, rg_real nx, rg_real ny)
{
    rg_real ox = b->owx[i], oy = b->owy[i];
    return (ox == 0 && oy == 0) || nx * ox + ny * oy > 0;
}

typedef struct sweep_task {
    rg_world *w;
} sweep_task;

#if RG_AVX2_PATHS
#include "avx2.h"

/* The places k .. k + 7 (consecutive bodies from dense i) whose body continuous_sweep_range
 * sweeps: dynamic, and moved more than half its smaller half extent (the same test). */
AVX2_FN static uint32_t continuous_fast8(const rg_world *w, int32_t k, int32_t i)
{
    const views_state *ns = &w->coll.views;
    const body_store *b = &w->b;
    __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(b->x + i), _mm256_loadu_ps(ns->sx0 + k));
    __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(b->y + i), _mm256_loadu_ps(ns->sy0 + k));
    __m256 h = _mm256_min_ps(_mm256_loadu_ps(b->hx + i), _mm256_loadu_ps(b->hy + i));
    __m256 fast = _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.25f), h), h), _CMP_GT_OQ);
    __m256i type = _mm256_loadu_si256((const __m256i *)(const void *)(b->type + i));
    __m256 dyn = _mm256_castsi256_ps(_mm256_cmpeq_epi32(type, _mm256_set1_epi32(RG_BODY_DYNAMIC)));
    return (uint32_t)_mm256_movemask_ps(_mm256_and_ps(fast, dyn));
}
#endif

/* Awake bodies [begin, end): each fast dynamic body against the immovable and sleeping
 * bodies it has contacts with, which no body of the sweep moves, so each body is its own.
 * Eight places of consecutive bodies at a time pass over those with no fast body
 * (continuous_fast8) where the CPU has AVX2. */
static void continuous_sweep_range(int32_t k0, int32_t k1, int32_t worker, void *context)
{
    rg_world *w = ((const sweep_task *)context)->w;
    collide_world *cw = &w->coll;
    const contact_store *cs = &cw->contacts;
    const views_state *ns = &cw->views;
    body_store *b = &w->b;
    (void)worker;
#if RG_AVX2_PATHS
    int wide = __builtin_cpu_supports("avx2");
#endif
    for (int32_t k = k0; k < k1; k++) {
        int32_t i = ns->adense[k];
#if RG_AVX2_PATHS
        /* at the start of each block of eight */
        if (wide && (k - k0) % 8 == 0 && k1 - k >= 8) {
            int run = 1;
            for (int l = 1; l < 8; l++) run &= ns->adense[k + l] == i + l;
            if (run && continuous_fast8(w, k, i) == 0) {
                k += 7;
                continue;
            }
        }
#endif
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        rg_vec2 p0 = rg_v2(ns->sx0[k], ns->sy0[k]), p1 = rg_v2(b->x[i], b->y[i]);
        rg_vec2 D = rg_v2_sub(p1, p0), hf = rg_v2(b->hx[i], b->hy[i]);
        rg_real h = rg_min(hf.x, hf.y);
        if (!(D.x * D.x + D.y * D.y > RG_R(0.25) * h * h)) continue;
        int32_t s = b->slot[i];
        rg_real tmin = 1;
        rg_vec2 nbest = rg_v2(0, 0), vbest = rg_v2(0, 0);
        for (int32_t id = b->chead[i] - 1; id >= 0; id = contact_next(&cs->c[id], s)) {
            const contact *c = &cs->c[id];
            if (c->flags & (CT_SENSOR | CT_PASS)) continue;
            int32_t j = body_dense(w, contact_other(c, s));
            int active = j < b->n_active;
            if (b->type[j] == RG_BODY_DYNAMIC && active) continue;
            rg_vec2 ho = rg_v2(b->hx[j], b->hy[j]);
            rg_vec2 o1 = rg_v2(b->x[j], b->y[j]);
            rg_vec2 dob = active ? rg_v2(b->dx[j], b->dy[j]) : rg_v2(0, 0);
            rg_vec2 o0 = rg_v2_sub(o1, dob);
            rg_real t;
            coll_manifold hit, end;
            if (!coll_sweep(b->shape[j], o0, ho, b->shape[i], p0, hf, rg_v2_sub(D, dob), &t, &hit)) continue;
            if (!(t > 0 && t < tmin)) continue;
            /* a one-way shape blocks only against its normal (hit.normal: from j toward i) */
            if ((c->flags & CT_ONEWAY) && (!continuous_one_way_blocks(b, j, hit.normal.x, hit.normal.y) ||
                                           !continuous_one_way_blocks(b, i, -hit.normal.x, -hit.normal.y)))
                continue;
            coll_manifold_of(b->shape[j], o1, ho, b->shape[i], p1, hf, &end);
            if (end.depth >= 0 && end.depth <= cw->slop) continue; /* resting at the end */
            tmin = t;
            nbest = hit.normal;
            vbest = active ? rg_v2(b->vx[j], b->vy[j]) : rg_v2(0, 0);
        }
        if (tmin >= 1) continue;
        rg_real len = rg_v2_len(D);
        rg_real tb = len > 0 ? rg_max(tmin - RG_R(0.5) * cw->slop / len, 0) : 0;
        b->x[i] = p0.x + D.x * tb;
        b->y[i] = p0.y + D.y * tb;
        rg_real vn = (b->vx[i] - vbest.x) * nbest.x + (b->vy[i] - vbest.y) * nbest.y;
        if (vn < 0) {
            b->vx[i] -= vn * nbest.x;
            b->vy[i] -= vn * nbest.y;
        }
    }
}

/* Bodies per sweep range (most are slow and skip at once). */
#define SWEEP_RANGE 256

void continuous_sweep(rg_world *w, const collide_step *x)
{
    if (!w->coll.continuous) return;
    sweep_task t = { w };
    task_for(w, continuous_sweep_range, x->na, SWEEP_RANGE, &t);
}
