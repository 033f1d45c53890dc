/* continuous.c: timed impacts and the post-solve sweep (see continuous.h). */
#include <string.h>

#include "body.h"
#include "broadphase.h"
#include "collision.h"
#include "contact.h"
#include "continuous.h"
#include "dispatch.h"
#include "island.h"
#include "pairs.h"
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

/* Whether dense body i, its box at p1 (half extents hf), left its fat box (or the box is due
 * for a refresh: !pairs_inside): the solve moved it where the step's pair search did not
 * look, so a shape it meets there may have no contact with it. */
static inline int continuous_left(const rg_world *w, int32_t i, rg_vec2 p1, rg_vec2 hf)
{
    rg_real box[4] = {p1.x - hf.x, p1.y - hf.y, p1.x + hf.x, p1.y + hf.y};
    return !pairs_inside(&w->coll.bp.e[w->b.slot[i]], box);
}

#if RG_AVX2_PATHS
#include "avx2.h"

/* The places k .. k + 7 (consecutive bodies from dense i) whose body
 * continuous_sweep_bodies sweeps: dynamic, and moved more than half its smaller half
 * extent, or by the solve more than the slop off its free motion (the same tests). */
AVX2_FN static uint32_t continuous_fast8(const rg_world *w, int32_t k, int32_t i)
{
    const views_state *ns = &w->coll.views;
    const body_store *b = &w->b;
    __m256 x1 = _mm256_loadu_ps(b->x + i), y1 = _mm256_loadu_ps(b->y + i);
    __m256 hx = _mm256_loadu_ps(b->hx + i), hy = _mm256_loadu_ps(b->hy + i);
    __m256 dx = _mm256_sub_ps(x1, _mm256_loadu_ps(ns->sx0 + k));
    __m256 dy = _mm256_sub_ps(y1, _mm256_loadu_ps(ns->sy0 + k));
    __m256 h = _mm256_min_ps(hx, hy);
    __m256 fast = _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.25f), h), h), _CMP_GT_OQ);
    __m256 px = _mm256_sub_ps(dx, _mm256_loadu_ps(b->dx + i)), py = _mm256_sub_ps(dy, _mm256_loadu_ps(b->dy + i));
    __m256 slop = _mm256_set1_ps(w->coll.slop);
    fast = _mm256_or_ps(fast, _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(px, px), _mm256_mul_ps(py, py)),
                                            _mm256_mul_ps(slop, slop), _CMP_GT_OQ));
    __m256i type = _mm256_loadu_si256((const __m256i *)(const void *)(b->type + i));
    __m256 dyn = _mm256_castsi256_ps(_mm256_cmpeq_epi32(type, _mm256_set1_epi32(RG_BODY_DYNAMIC)));
    return (uint32_t)_mm256_movemask_ps(_mm256_and_ps(fast, dyn));
}
#endif

/* One leg of a body's sweep: from p0 along D to p1 (half extents hf) over the last `rest` of
 * the step, and the first impact so far (tmin, a fraction of the leg; the hit surface's
 * normal from the other body toward it, that body's velocity, its motion over the whole
 * step and its slot). */
typedef struct sweep_body {
    const rg_world *w;
    int32_t i, s; /* dense index and slot */
    rg_vec2 p0, p1, D, hf;
    rg_real rest;
    rg_real tol;  /* grazing tolerance (coll_graze_normal), m */
    rg_real tmin;
    rg_vec2 nbest, vbest, dbest;
    int32_t sbest;
    int sleeping; /* the body of the first impact is asleep */
} sweep_body;

/* Whether dense body j is one the sweep meets: immovable, or asleep. */
static inline int continuous_met(const body_store *b, int32_t j)
{
    return b->type[j] != RG_BODY_DYNAMIC || j >= b->n_active;
}

/* Dense body j (immovable, or asleep) against the sweep: a hit before the first so far, that
 * a one-way shape blocks and that does not leave the body resting on j, becomes the first. */
static void continuous_meet(sweep_body *sb, int32_t j)
{
    const rg_world *w = sb->w;
    const body_store *b = &w->b;
    int32_t i = sb->i;
    int active = j < b->n_active;
    rg_vec2 ho = rg_v2(b->hx[j], b->hy[j]);
    rg_vec2 o1 = rg_v2(b->x[j], b->y[j]);
    rg_vec2 dstep = active ? rg_v2(b->dx[j], b->dy[j]) : rg_v2(0, 0);
    rg_vec2 dob = rg_v2_scale(dstep, sb->rest); /* j's motion over the leg */
    rg_vec2 o0 = rg_v2_sub(o1, dob);
    rg_real t;
    coll_manifold hit, end;
    rg_vec2 rel = rg_v2_sub(sb->D, dob);
    if (!coll_sweep(b->shape[j], o0, ho, b->shape[i], sb->p0, sb->hf, rel, &t, &hit)) return;
    if (!(t < sb->tmin)) return;
    rg_vec2 n = hit.normal;
    if (t > 0 && b->shape[j] == RG_SHAPE_AABB) {
        /* flush with a face of box j where they meet and moving along it: it grazes the face
         * (a tile seam), as the mover's legs do */
        rg_vec2 cj = rg_v2_add(o0, rg_v2_scale(dob, t)), pi = rg_v2_add(sb->p0, rg_v2_scale(sb->D, t));
        n = coll_graze_normal(cj, ho, pi, sb->hf, rel, n, sb->tol);
        if (!(rg_v2_dot(rel, n) < -COLL_INTO * rg_v2_len(rel))) return;
    }
    /* touching or overlapping j at the start (t = 0, hit.normal the normal of least
     * penetration): met only where the motion goes into j by more than the slop (a body
     * flush against a thin wall that the solve pushes through it), not where it leaves j or
     * slides along it (a slider's motion into the surface it rests on is rounding) */
    if (!(t > 0) && !(rg_v2_dot(rel, hit.normal) < -w->coll.slop)) return;
    /* a one-way shape blocks only against its normal (hit.normal: from j toward i); a two-way
     * one always */
    if (!continuous_one_way_blocks(b, j, n.x, n.y) || !continuous_one_way_blocks(b, i, -n.x, -n.y)) return;
    coll_manifold_of(b->shape[j], o1, ho, b->shape[i], sb->p1, sb->hf, &end);
    /* resting at the end, on the side it hit (a body through to the far side, just touching
     * it there, is not resting) */
    if (end.depth >= 0 && end.depth <= w->coll.slop && rg_v2_dot(end.normal, n) > 0) return;
    sb->tmin = t;
    sb->nbest = n;
    sb->vbest = active ? rg_v2(b->vx[j], b->vy[j]) : rg_v2(0, 0);
    sb->dbest = dstep;
    sb->sbest = b->slot[j];
    sb->sleeping = b->type[j] == RG_BODY_DYNAMIC;
}

/* A member of the broadphase on the path of a body that left its fat box: a shape the sweep
 * meets (continuous_met) and the filter admits, sensors aside, that the body has no contact
 * with (its contacts are swept already, and a contact passing through is not met). */
static void continuous_visit(void *ctx, int32_t t)
{
    sweep_body *sb = ctx;
    const rg_world *w = sb->w;
    const body_store *b = &w->b;
    const contact_store *cs = &w->coll.contacts;
    if (t == sb->s) return;
    int32_t j = body_dense(w, t);
    if (!continuous_met(b, j)) return;
    if (((b->cflags[sb->i] | b->cflags[j]) & CF_SENSOR) || !pairs_admitted(w, sb->i, j)) return;
    for (int32_t id = b->chead[sb->i] - 1; id >= 0; id = contact_next(&cs->c[id], sb->s))
        if (contact_other(&cs->c[id], sb->s) == t) return;
    continuous_meet(sb, j);
}

/* The first impact on the leg in sb: the bodies the pass meets that the body has contacts
 * with, and, where the leg may leave its fat box (left), those on its path it has none with. */
static void continuous_leg(sweep_body *sb, int left)
{
    const rg_world *w = sb->w;
    const body_store *b = &w->b;
    const contact_store *cs = &w->coll.contacts;
    sb->tmin = 1;
    sb->nbest = sb->vbest = sb->dbest = rg_v2(0, 0);
    sb->sbest = -1;
    sb->sleeping = 0;
    for (int32_t id = b->chead[sb->i] - 1; id >= 0; id = contact_next(&cs->c[id], sb->s)) {
        const contact *c = &cs->c[id];
        if (c->flags & (CT_SENSOR | CT_PASS | CT_SKIPPED)) continue;
        int32_t j = body_dense(w, contact_other(c, sb->s));
        if (continuous_met(b, j)) continuous_meet(sb, j);
    }
    if (left)
        broadphase_query(&w->coll.bp, rg_min(sb->p0.x, sb->p1.x) - sb->hf.x, rg_min(sb->p0.y, sb->p1.y) - sb->hf.y,
                         rg_max(sb->p0.x, sb->p1.x) + sb->hf.x, rg_max(sb->p0.y, sb->p1.y) + sb->hf.y,
                         continuous_visit, sb);
}

/* Legs of a body's sweep: after an impact with an immovable body the rest of the motion goes
 * on along the surface (relative to that body, which carries it along), as the mover's. */
#define SWEEP_LEGS 4

/* Awake bodies [k0, k1): each dynamic body that moved more than half its size, or that the
 * solve moved more than the slop off its free motion, against the static, kinematic and
 * sleeping bodies it has contacts with, and, out of its fat box, against those on its path
 * it has none with.  A push of less than SPECULATIVE * slop meets no pair the step did not
 * solve, and one of less than the slop leaves the fat box (which holds the box moved by the
 * free motion: views_build) by less than the slop.  Nothing moves the bodies met, so each
 * body is its own: it slides on from an immovable one (up to SWEEP_LEGS legs, the last
 * stopped at its impact) and stops at a sleeping one, which sweep.stop[k] names for
 * continuous_wake.  Eight places of consecutive bodies at a time pass over those with no
 * such body (continuous_fast8) where the CPU has AVX2. */
static void continuous_sweep_bodies(rg_world *w, int32_t k0, int32_t k1)
{
    collide_world *cw = &w->coll;
    const views_state *ns = &cw->views;
    sweep_state *ss = &cw->sweep;
    body_store *b = &w->b;
#if RG_AVX2_PATHS
    int wide = __builtin_cpu_supports("avx2");
#endif
    for (int32_t k = k0; k < k1; k++) {
        int32_t i = ns->adense[k];
        ss->stop[k] = -1;
#if RG_AVX2_PATHS
        /* at the start of each block of eight */
        if (wide && (k - k0) % 8 == 0 && k1 - k >= 8) {
            int run = 1;
            for (int l = 1; l < 8; l++) run &= ns->adense[k + l] == i + l;
            if (run && continuous_fast8(w, k, i) == 0) {
                for (int l = 1; l < 8; l++) ss->stop[k + l] = -1;
                k += 7;
                continue;
            }
        }
#endif
        if (b->type[i] != RG_BODY_DYNAMIC) continue;
        sweep_body sb;
        sb.w = w;
        sb.i = i;
        sb.s = b->slot[i];
        sb.p0 = rg_v2(ns->sx0[k], ns->sy0[k]);
        sb.p1 = rg_v2(b->x[i], b->y[i]);
        sb.D = rg_v2_sub(sb.p1, sb.p0);
        sb.hf = rg_v2(b->hx[i], b->hy[i]);
        sb.tol = cw->slop + 64 * RG_EPSILON * (rg_fabs(sb.p0.x) + rg_fabs(sb.p0.y) + sb.hf.x + sb.hf.y);
        rg_real h = rg_min(sb.hf.x, sb.hf.y);
        rg_vec2 pushed = rg_v2(sb.D.x - b->dx[i], sb.D.y - b->dy[i]);
        if (!(sb.D.x * sb.D.x + sb.D.y * sb.D.y > RG_R(0.25) * h * h) &&
            !(pushed.x * pushed.x + pushed.y * pushed.y > cw->slop * cw->slop))
            continue;
        int left = continuous_left(w, i, sb.p1, sb.hf);
        sb.rest = 1;
        for (int leg = 0;; leg++) {
            continuous_leg(&sb, left);
            if (sb.tmin >= 1) break;
            rg_real len = rg_v2_len(sb.D);
            rg_real tb = len > 0 ? rg_max(sb.tmin - RG_R(0.5) * cw->slop / len, 0) : 0;
            rg_vec2 at = rg_v2(sb.p0.x + sb.D.x * tb, sb.p0.y + sb.D.y * tb);
            b->x[i] = at.x;
            b->y[i] = at.y;
            if (sb.sleeping) {
                ss->stop[k] = sb.sbest;
                ss->nx[k] = sb.nbest.x;
                ss->ny[k] = sb.nbest.y;
                break;
            }
            rg_real vn = (b->vx[i] - sb.vbest.x) * sb.nbest.x + (b->vy[i] - sb.vbest.y) * sb.nbest.y;
            if (vn < 0) {
                b->vx[i] -= vn * sb.nbest.x;
                b->vy[i] -= vn * sb.nbest.y;
            }
            if (leg == SWEEP_LEGS - 1) break;
            /* the rest of the step: the motion relative to the body met, less its part into
             * the surface, and the body met's own motion, from where it met */
            rg_real rest = sb.rest * (1 - sb.tmin);
            rg_vec2 rel = rg_v2_scale(rg_v2_sub(sb.D, rg_v2_scale(sb.dbest, sb.rest)), 1 - sb.tmin);
            rg_real into = rg_v2_dot(rel, sb.nbest);
            if (into < 0) rel = rg_v2_sub(rel, rg_v2_scale(sb.nbest, into));
            sb.D = rg_v2_add(rel, rg_v2_scale(sb.dbest, rest));
            sb.p0 = at;
            sb.p1 = rg_v2_add(at, sb.D);
            sb.rest = rest;
            if (!(sb.D.x != 0 || sb.D.y != 0)) break;
            left = left || continuous_left(w, i, sb.p1, sb.hf);
            b->x[i] = sb.p1.x;
            b->y[i] = sb.p1.y;
        }
    }
}

/* On the stepping thread, in order: each body the sweep stopped at a sleeping one that it
 * approaches hands it its momentum along the normal, as an inelastic impact of the two, once
 * it is awake (its dense index moves with the wake).  Returns whether it woke one. */
static int continuous_wake(rg_world *w, int32_t n)
{
    const views_state *ns = &w->coll.views;
    const sweep_state *ss = &w->coll.sweep;
    body_store *b = &w->b;
    int woke = 0;
    for (int32_t k = 0; k < n; k++) {
        int32_t s = ss->stop[k];
        if (s < 0) continue;
        int32_t i = ns->adense[k], j = body_dense(w, s);
        rg_vec2 nb = rg_v2(ss->nx[k], ss->ny[k]);
        rg_real vn = (b->vx[i] - b->vx[j]) * nb.x + (b->vy[i] - b->vy[j]) * nb.y;
        if (!(vn < 0)) continue;
        if (j >= b->n_active) {
            island_wake(w, s);
            woke = 1;
            j = body_dense(w, s);
        }
        rg_real ima = b->inv_mass[i], imb = b->inv_mass[j];
        rg_real p = -vn / (ima + imb);
        b->vx[i] += p * ima * nb.x;
        b->vy[i] += p * ima * nb.y;
        b->vx[j] -= p * imb * nb.x;
        b->vy[j] -= p * imb * nb.y;
    }
    return woke;
}

static void continuous_sweep_range(int32_t k0, int32_t k1, int32_t worker, void *context)
{
    (void)worker;
    continuous_sweep_bodies(((const sweep_task *)context)->w, k0, k1);
}

/* Bodies per sweep range (most are slow and skip at once). */
#define SWEEP_RANGE 256

int continuous_sweep(rg_world *w, const collide_step *x)
{
    if (!w->coll.continuous) return 0;
    sweep_task t = { w };
    /* the bodies awake at the start, and those woken since (views_woken) */
    int32_t n = x->woke ? w->coll.bp.n_active : x->na;
    task_for(w, continuous_sweep_range, n, SWEEP_RANGE, &t);
    /* the sleeping bodies met, on this thread: it wakes them */
    if (w->b.n_moving == w->b.n_active) return 0;
    return continuous_wake(w, n);
}
