/* narrow.c: the narrowphase (see narrow.h). */
#include <string.h>

#include "body.h"
#include "collision.h"
#include "events.h"
#include "inline.h"
#include "island.h"
#include "narrow.h"
#include "narrow_reach.h"
#include "narrow_wide.h"
#include "resolve.h"
#include "state.h"
#include "task.h"
#include "vec2.h"
#include "views.h"

static int narrow_pusher(const body_store *b, int32_t j, int touching)
{
    if (b->type[j] == RG_BODY_DYNAMIC) return touching;
    return b->type[j] == RG_BODY_KINEMATIC && (b->vx[j] != 0 || b->vy[j] != 0);
}

/* Grounded flag of a body with gravity scale gs touching a surface whose normal, pointing
 * toward the body, is (nx, ny): the normal points against its gravity within 45 degrees. */
static inline int narrow_is_ground(rg_real gx, rg_real gy, rg_real gs, rg_real nx, rg_real ny)
{
    rg_real ex = gx * gs, ey = gy * gs;
    rg_real up = -(nx * ex + ny * ey);
    rg_real g2 = ex * ex + ey * ey;
    return g2 > 0 && up > 0 && up * up >= COS45 * COS45 * g2;
}

/* The ND_GROUND_* bits of touching solid contact c between views A and B. */
static inline uint32_t narrow_grounded(const rg_world *w, const contact *c, const cbody *A, const cbody *B)
{
    uint32_t bits = 0;
    if (A->gs != 0 && narrow_is_ground(w->gravity.x, w->gravity.y, A->gs, -c->nx, -c->ny)) bits |= ND_GROUND_A;
    if (B->gs != 0 && narrow_is_ground(w->gravity.x, w->gravity.y, B->gs, c->nx, c->ny)) bits |= ND_GROUND_B;
    return bits;
}

/* Whether one-way body P (any body: two-way ones always block) blocks body O of a contact
 * that begins with normal (nx, ny) from P toward O and start separation s0: the normal points
 * to the side of P's one-way normal n and the shapes overlap by no more than the slop, or O's
 * shape lay wholly on that side at the start of the step, its extent along n beginning no more
 * than the slop short of the end of P's (for n = (0, 1): O's bottom at or above P's top minus
 * the slop).  The second test is for a box sliding over flush one-way tiles: it meets the
 * next tile's corner first, with a side normal, while it rests on their tops all along. */
static inline int narrow_one_way_blocks(const body_store *b, int32_t ip, const cbody *P, const cbody *O,
                                        rg_real nx, rg_real ny, rg_real s0, rg_real slop)
{
    rg_real ox = b->owx[ip], oy = b->owy[ip];
    if (ox == 0 && oy == 0) return 1;
    if (nx * ox + ny * oy > 0 && s0 >= -slop) return 1;
    /* a shape's reach along the unit n from its centre: r, or the box's corner */
    rg_real rp = P->kind == RG_SHAPE_CIRCLE ? P->hx : rg_fabs(ox) * P->hx + rg_fabs(oy) * P->hy;
    rg_real ro = O->kind == RG_SHAPE_CIRCLE ? O->hx : rg_fabs(ox) * O->hx + rg_fabs(oy) * O->hy;
    rg_real gap = ((O->sx - P->sx) * ox + (O->sy - P->sy) * oy) - ro - rp;
    return gap >= -slop;
}

/* Whether the pair is skipped (neither solved nor touching) this step: it is passing through
 * (rg_body_pass_through, or a one-way body it met from the wrong side or inside, until a
 * step ends with the shapes apart, d > 0), or the pre-solve hook says so.  `candidate`: the
 * pair would be solved or touching.  A touching one-way contact keeps blocking. */
static int narrow_skip(rg_world *w, contact *c, int32_t ia, int32_t ib, const cbody *A, const cbody *B,
                       rg_real s0, rg_real d, uint32_t was, int candidate)
{
    if (c->flags & CT_PASS) {
        if (d > 0) c->flags &= ~CT_PASS; /* apart at the end of this step: collides from the next */
        return 1;
    }
    if (!candidate) return 0;
    if ((c->flags & CT_ONEWAY) && !was) {
        const body_store *b = &w->b;
        rg_real slop = w->coll.slop;
        if (!narrow_one_way_blocks(b, ia, A, B, c->nx, c->ny, s0, slop) ||
            !narrow_one_way_blocks(b, ib, B, A, -c->nx, -c->ny, s0, slop)) {
            if (!(d > 0)) c->flags |= CT_PASS;
            return 1;
        }
    }
    if (w->pre_solve != NULL && !(c->flags & CT_SENSOR)) {
        /* the step holds the world's lock (step.c) */
        int32_t keep = w->pre_solve(pool_handle(&w->body_pool, c->sa), pool_handle(&w->body_pool, c->sb),
                                    rg_v2(c->nx, c->ny), s0, w->pre_solve_user);
        if (!keep) {
            c->flags |= CT_SKIPPED; /* the sweep lets it pass too */
            return 1;
        }
    }
    return 0;
}

typedef struct narrow_task {
    rg_world *w;
    collide_step *x;
    int wide;                         /* narrow_wide_ready */
    int32_t n;                        /* the contacts measured and decided in parallel */
    int stage;                        /* and staged in parallel, into the spare rows */
    const int32_t *handed;            /* with stage: the blocks in the order the tasks take
                                       * them (narrow_hand) */
    int32_t in_order[RG_MAX_WORKERS]; /* the worker met a contact decided in order */
    int32_t sensed[RG_MAX_WORKERS];   /* the worker met a sensor pair */
} narrow_task;

/* The measurement and the decision are inlined into the two walks that use them (the
 * parallel ranges and the serial walk): as calls, their arguments and the contact's fields
 * went through memory (3% of rain 4000's instructions).
 *
 * The measurement of contact id (the broadphase keeps only pairs whose fat boxes overlap):
 * the manifold at the start of the step or at the time of impact.  It reads the step's views
 * and writes only the contact's own fields, so the contacts are measured in parallel ranges
 * (narrow_run) before the rest runs in order.  A pair far apart (far: narrow_far) is left to
 * narrow_decide.  Otherwise: CT_ACTIVE when the pair meets within the step, with its normal,
 * point and start separation in nx, ny, px, py, s0. */
static FORCE_INLINE void narrow_measure(const rg_world *w, contact *c, const cbody *A, const cbody *B, int far)
{
    const collide_world *cw = &w->coll;
    int32_t ka = A->kind, kb = B->kind;
    rg_vec2 ha = rg_v2(A->hx, A->hy), hb = rg_v2(B->hx, B->hy);
    rg_vec2 r = rg_v2(B->dx - A->dx, B->dy - A->dy); /* b's motion relative to a over the step */
    if (far || (c->flags & CT_SENSOR)) return; /* a sensor is measured where the step ends (sense.h) */
    coll_manifold m;
    rg_real s0 = RG_HUGE;
    int active = 1;
    if (!cw->continuous) {
        /* discrete: the shapes where the step left them, extrapolated back */
        coll_manifold_of(ka, rg_v2(A->sx + A->dx, A->sy + A->dy), ha, kb, rg_v2(B->sx + B->dx, B->sy + B->dy), hb, &m);
        s0 = -m.depth - rg_v2_dot(r, m.normal);
    } else {
        if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) {
            /* the common case inline: two circles at the start of the step */
            rg_real ex = B->sx - A->sx, ey = B->sy - A->sy;
            rg_real dist = rg_sqrt(ex * ex + ey * ey);
            rg_real nx = 0, ny = 1;
            if (dist > 0) {
                rg_real inv = 1 / dist;
                nx = ex * inv;
                ny = ey * inv;
            }
            m.normal = rg_v2(nx, ny);
            s0 = dist - ha.x - hb.x;
            rg_real f = ha.x + RG_R(0.5) * s0; /* halfway between the surfaces, from a */
            m.point = rg_v2(A->sx + nx * f, A->sy + ny * f);
        } else if (ka == RG_SHAPE_AABB && kb == RG_SHAPE_AABB) {
            /* two boxes inline too: coll_contact's operations */
            coll_contact_boxes(rg_v2(A->sx, A->sy), ha, rg_v2(B->sx, B->sy), hb, r, cw->slop, &m);
            s0 = -m.depth;
        } else {
            coll_contact(ka, rg_v2(A->sx, A->sy), ha, kb, rg_v2(B->sx, B->sy), hb, r, cw->slop, &m);
            s0 = -m.depth;
        }
        /* apart at the start and fast (moving more than half the smaller shape): the time
         * of impact instead.  Where the free motion misses a static, kinematic or sleeping
         * body (im 0), the pair stays a speculative row at the start's gap if that motion
         * keeps the gap open along the start's normal (as a slow pair would: the row holds
         * against motion the solve gives, an impact from the other side, which would else
         * push the body into a thin shape it has no row with); where that motion would close
         * it, the pair passes beside: no row.  Two movable bodies that miss get none. */
        rg_real size = rg_min(rg_min(ha.x, ha.y), rg_min(hb.x, hb.y));
        if (s0 > cw->slop && !(r.x * r.x + r.y * r.y <= RG_R(0.25) * size * size)) {
            rg_real t;
            coll_manifold start = m;
            if (coll_sweep(ka, rg_v2(A->sx, A->sy), ha, kb, rg_v2(B->sx, B->sy), hb, r, &t, &m))
                s0 = t > 0 ? -t * rg_v2_dot(r, m.normal) : -m.depth;
            else if ((A->im == 0 || B->im == 0) && s0 + rg_v2_dot(r, start.normal) > 0)
                m = start;
            else
                active = 0;
        }
    }
    if (active) {
        c->flags |= CT_ACTIVE;
        c->nx = m.normal.x;
        c->ny = m.normal.y;
        c->px = m.point.x;
        c->py = m.point.y;
        c->s0 = s0;
    }
}

/* (narrow_decide's ND_* bits: narrow_wide.h) */

/* Whether the pair's decision needs the stepping thread: a one-way body or passing through
 * (their state changes in order), or a pre-solve hook (a callback, in order). */
static inline int narrow_in_order(const rg_world *w, const contact *c)
{
    return (c->flags & (CT_ONEWAY | CT_PASS)) || w->pre_solve != NULL;
}

/* Whether dense body ia or ib is movable and was asleep when the step began (its index at
 * or past the step's awake count n, before a wake in the step and after it). */
static inline int narrow_asleep_movable(const rg_real *inv_mass, int32_t ia, int32_t ib, int32_t n)
{
    return (ia >= n && inv_mass[ia] > 0) || (ib >= n && inv_mass[ib] > 0);
}

/* Decides contact c between dense bodies ia, ib (views A, B) from its measurement: touching,
 * solved, its flags, vn0 and toi, and the begin's depth and speed; writes only the contact's
 * own fields, so the contacts that need no order (narrow_in_order) decide in parallel.
 * far: narrow_far, as the measurement had it.  in_order: the skip (narrow_skip) may be
 * asked.  n: the step's awake count (x->n).  Returns ND_* bits. */
static FORCE_INLINE uint32_t narrow_decide(rg_world *w, contact *c, int32_t ia, int32_t ib, int32_t n,
                                            const cbody *A, const cbody *B, int far, int in_order)
{
    const collide_world *cw = &w->coll;
    rg_vec2 r = rg_v2(B->dx - A->dx, B->dy - A->dy); /* b's motion relative to a over the step */
    if (c->flags & CT_SENSOR) {
        /* never solved; touching where the step ends, once every body is placed (sense.h) */
        c->flags &= ~(CT_ACTIVE | CT_SOLVE | CT_CLOSING);
        c->pn = c->pt = 0;
        return ND_SENSOR | ((c->flags & CT_TOUCHING) ? ND_NOW | ND_WAS : 0);
    }
    if (far) {
        /* what the full test would conclude: not solved, not touching, apart */
        c->flags &= ~(CT_SOLVE | CT_CLOSING | CT_PASS);
        c->pn = c->pt = 0;
        return 0;
    }
    int active = (c->flags & CT_ACTIVE) != 0;
    rg_real s0 = c->s0;
    c->flags &= ~CT_ACTIVE;
    uint32_t was = c->flags & CT_TOUCHING, now = 0, bits = 0;
    c->flags &= ~(CT_SOLVE | CT_CLOSING);
    if (!active) c->flags &= ~CT_PASS; /* no impact within the step: apart */
    if (active) {
        rg_real nx = c->nx, ny = c->ny;
        rg_real vn0 = (B->vx - A->vx) * nx + (B->vy - A->vy) * ny;
        rg_real d = s0 + r.x * nx + r.y * ny; /* predicted separation */
        rg_real reach_o = 0, d_o = 0, d_v = d;
        if (cw->offk > 0) {
            /* Explicit Euler, Verlet, RK4: the views hold v dt, the motion the rows hold; the
             * integrator's own ends o off it, which a body the rows leave alone keeps
             * (resolve.c).  The pair closes, touches and is solved when either motion
             * does (d_o: the integrator's), and an impact is timed on the integrator's
             * motion (below). */
            rg_vec2 oa = narrow_off(cw, A), ob = narrow_off(cw, B);
            rg_real on = (ob.x - oa.x) * nx + (ob.y - oa.y) * ny;
            d_o = d + on;
            if (d < 0 && !(d_o < 0) && s0 > 0 && !was) {
                /* only v dt closes the gap (o takes the body away from the other, as
                 * gravity over a floor): its own motion does not reach the surface in this
                 * step, so the pair is apart, and its row holds that motion (its gap at the
                 * start taken as s0 + o along n: vmin = -(s0 + o n) / dt, staging), for the
                 * impact to be timed in the next step */
                s0 += on;
                c->s0 = s0;
                d = d_o;
            }
            d = rg_min(d, d_o);
            reach_o = rg_fabs(oa.x * nx + oa.y * ny) + rg_fabs(ob.x * nx + ob.y * ny);
        }
        /* touching: the step ends with the pair in contact (the free motion closes the gap,
         * which the solver then holds); a slop of hysteresis keeps resting pairs steady */
        if (d <= 0 || (was && d < cw->slop)) now = CT_TOUCHING;
        c->vn0 = vn0;
        if (d < 0) c->flags |= CT_CLOSING;
        /* solved when the pair could close within the step: not only by the free motion
         * (d), but also when the solver stops either body (an impact below it) while the
         * other moves on, so each body's own motion toward the other counts */
        rg_real reach = rg_fabs(A->dx * nx + A->dy * ny) + rg_fabs(B->dx * nx + B->dy * ny) + reach_o;
        int solve = !(c->flags & CT_SENSOR) && s0 - reach < SPECULATIVE * cw->slop && rg_finite(s0) &&
                    rg_finite(vn0);
        /* one-way shapes, pass-through and the pre-solve hook may skip the pair this step */
        if (in_order && narrow_in_order(w, c) && narrow_skip(w, c, ia, ib, A, B, s0, d, was, now != 0 || solve)) {
            now = 0;
            solve = 0;
            c->flags &= ~CT_CLOSING;
        }
        /* Solved where a body moves: in this step's rows, which see a body asleep at the
         * step's start as the ground (its view's im is 0), or, where such a body is movable,
         * in the rows staged again if it wakes in this step (resolve.c's restage, which
         * reads CT_SOLVE): a stack woken by a body landing on it holds in the step that
         * wakes it.  The pair keeps its impulse for that row's warm start. */
        int moves = A->im + B->im > 0;
        if (solve && (moves || narrow_asleep_movable(w->b.inv_mass, ia, ib, n))) {
            c->flags |= CT_SOLVE;
            /* An impact: the free motion closes the gap of a pair that was apart, at the
             * fraction toi of the step (the solve decides whether to time it).  A pair in
             * contact (touching after the last step, or overlapping) has toi 0: it may carry
             * weight or pass on an impulse at any moment of the step.  A pair apart that the
             * free motion does not close has toi -1. */
            rg_real toi = was || s0 <= 0 ? 0 : -1;
            if (d < 0) toi = s0 > 0 && !was ? s0 / (s0 - d) : 0;
            if (d_o < 0 && toi > 0) {
                /* timed on the integrator's own motion, which closes the gap: s0 + vn0 dt u
                 * + q u^2 at the fraction u of the step, q = -(2 - 2 offk) o n (explicit
                 * Euler moves by v0 dt: q 0; Verlet and RK4 by v0 dt + a dt^2 / 2: q = -o n);
                 * its one root in (0, 1), as 2 s0 / (-b + sqrt(b^2 - 4 q s0)) */
                rg_real bq = vn0 * cw->offdt, qq = -(2 - 2 * cw->offk) * (d_o - d_v);
                rg_real disc = bq * bq - 4 * qq * s0, den = disc >= 0 ? -bq + rg_sqrt(disc) : 0;
                rg_real u = den > 0 ? 2 * s0 / den : s0 / (s0 - d_o);
                toi = u > 0 && u < 1 ? u : s0 / (s0 - d_o);
            }
            c->toi = toi;
            if (moves) bits |= ND_STAGE;
        }
    }
    if (!(c->flags & CT_SOLVE)) c->pn = c->pt = 0;
    if (now != was) {
        c->flags ^= CT_TOUCHING;
        if (now) {
            c->depth = rg_max(-c->s0, 0);
            c->speed = rg_max(-c->vn0, 0);
        }
        bits |= now ? ND_BEGIN : ND_END;
    }
    if (now) bits |= narrow_grounded(w, c, A, B);
    return bits | (now ? ND_NOW : 0) | (was ? ND_WAS : 0);
}

/* Awake contacts [k0, k1) (at most NARROW_WIDE_LANES) with their bodies and views, and what
 * narrow_wide_decide did of them (wide: the step may use it). */
typedef struct narrow_block {
    int32_t n;
    uint32_t done;                          /* lanes measured and decided wide */
    narrow_lanes in;                        /* the lanes past n repeat lane 0's views */
    contact *c[NARROW_WIDE_LANES];
    int32_t ia[NARROW_WIDE_LANES], ib[NARROW_WIDE_LANES];
    uint32_t bits[NARROW_WIDE_LANES];       /* the done lanes' ND_* bits */
    int32_t id[NARROW_WIDE_LANES];          /* the lanes' contact ids */
    cbody rest[2 * NARROW_WIDE_LANES];      /* views of bodies at rest */
} narrow_block;

static FORCE_INLINE void narrow_block_run(rg_world *w, collide_step *x, int32_t k0, int32_t k1, int wide,
                                          narrow_block *nb, narrow_wide_stage *st)
{
    /* in locals: the stores into nb could alias them, which would read them again */
    contact *const cc = w->coll.contacts.c;
    const int32_t *const awake = w->coll.contacts.awake;
    const cbody *const cb = w->coll.views.cb;
    const int32_t nv = x->n;
    const rg_real *const inv_mass = w->b.inv_mass;
    int32_t n = nb->n = k1 - k0;
    nb->done = 0;
    nb->in.asleep = 0;
    if (st != NULL) st->staged = 0;
    for (int32_t l = 0; l < n; l++) {
        contact *c = nb->c[l] = &cc[nb->id[l] = awake[k0 + l]];
        int32_t ia = nb->ia[l] = body_dense(w, c->sa), ib = nb->ib[l] = body_dense(w, c->sb);
        if (narrow_asleep_movable(inv_mass, ia, ib, nv)) nb->in.asleep |= 1u << l;
        const cbody *a = nb->in.a[l] = ia < nv ? &cb[ia] : views_of(w, ia, nv, &nb->rest[2 * l]);
        const cbody *b = nb->in.b[l] = ib < nv ? &cb[ib] : views_of(w, ib, nv, &nb->rest[2 * l + 1]);
        nb->in.flags[l] = c->flags;
        nb->in.kind_a[l] = a->kind;
        nb->in.kind_b[l] = b->kind;
    }
#if RG_AVX2_PATHS
    if (!wide) return;
    for (int32_t l = n; l < NARROW_WIDE_LANES; l++) {
        nb->in.a[l] = nb->in.a[0];
        nb->in.b[l] = nb->in.b[0];
        nb->in.flags[l] = CT_ACTIVE;
        nb->in.kind_a[l] = nb->in.kind_b[l] = 0;
    }
    if (st != NULL) {
        st->ia = nb->ia;
        st->ib = nb->ib;
        st->id = nb->id;
    }
    nb->done = narrow_wide_decide(w, &nb->in, nb->c, nb->bits, st);
#else
    (void)wide;
    (void)st;
#endif
}

/* Joins the islands of a touching or solved pair of awake dynamic bodies (dense ia, ib). */
static void narrow_unite(rg_world *w, const contact *c, const collide_step *x, int32_t ia, int32_t ib)
{
    collide_world *cw = &w->coll;
    const body_store *b = &w->b;
    int32_t pa = cw->bp.e[c->sa].apos, pb = cw->bp.e[c->sb].apos;
    if (pa >= 0 && pb >= 0 && pa < x->na && pb < x->na && b->type[ia] == RG_BODY_DYNAMIC &&
        b->type[ib] == RG_BODY_DYNAMIC)
        island_unite(cw->island.uf, pa, pb);
}

/* The contact's begin or end (if its decision has one): the event and the touching count. */
static void narrow_events_of(rg_world *w, const contact *c, uint32_t bits)
{
    contact_store *cs = &w->coll.contacts;
    if (bits & ND_BEGIN) {
        cs->n_touching++;
        events_emit(w, c, RG_CONTACT_BEGIN);
    } else if (bits & ND_END) {
        cs->n_touching--;
        events_emit(w, c, RG_CONTACT_END);
    }
}

/* Stages contact id's row into d with the views' inverse masses: an awake body's (dense
 * below x->n), else 0. */
static FORCE_INLINE void narrow_stage_row(const rg_world *w, const collide_step *x, const solver_dest *d,
                                          int32_t id, int32_t ia, int32_t ib)
{
    const cbody *cb = w->coll.views.cb;
    resolve_stage(w, x, d, id, ia, ib, ia < x->n ? cb[ia].im : 0, ib < x->n ? cb[ib].im : 0);
}

/* What a contact's decision does to the rest of the world, in contact order: its solver row
 * (into d, unless NULL), events, grounded flags, islands (unite: x->unite), waking (on the
 * stepping thread, or, where nothing wakes and the rows are staged, beside the solve's first
 * part: narrow_commit_late). */
static FORCE_INLINE void narrow_commit(rg_world *w, int32_t id, int32_t ia, int32_t ib, collide_step *x,
                                       uint32_t bits, const solver_dest *d, int unite, int *woke)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    body_store *b = &w->b;
    contact *c = &cs->c[id];
    if ((bits & ND_STAGE) && d != NULL) narrow_stage_row(w, x, d, id, ia, ib);
    if (bits & ND_SENSOR) x->sensed = 1;
    narrow_events_of(w, c, bits);
    if (c->flags & CT_SENSOR) return;
    if (bits & ND_GROUND_A) b->cflags[ia] |= CF_GROUNDED;
    if (bits & ND_GROUND_B) b->cflags[ib] |= CF_GROUNDED;
    /* A solved pair links its bodies as a touching one does: the solve may push one with
     * the other, so they sleep and wake together (as Box2D v3's speculative contacts do) */
    int solved = (c->flags & CT_SOLVE) != 0;
    if (((bits & ND_NOW) || solved) && unite) narrow_unite(w, c, x, ia, ib);
    /* a sleeping body (dense index past the awake ones) touched by a pusher, or in a solved
     * pair with it, wakes (woke NULL: no body is asleep): asleep, the solve would take it for
     * the ground, and a row of bodies a few millimetres apart, hit at one end, would throw
     * the hit back as a wall does */
    if (woke != NULL && ((bits & (ND_NOW | ND_WAS)) || solved) && (ia >= b->n_active || ib >= b->n_active)) {
        int pa_ = body_partition(w, ia), pb_ = body_partition(w, ib);
        int now = (bits & ND_NOW) != 0 || solved;
        if (pa_ == BODY_PART_ASLEEP && pb_ == BODY_PART_ACTIVE && narrow_pusher(b, ib, now)) {
            island_wake(w, c->sa);
            *woke = 1;
        } else if (pb_ == BODY_PART_ASLEEP && pa_ == BODY_PART_ACTIVE && narrow_pusher(b, ia, now)) {
            island_wake(w, c->sb);
            *woke = 1;
        }
    }
}

/* A contact decided on the stepping thread: those in order, and those waking appended. */
static inline uint32_t narrow_decide_here(rg_world *w, contact *c, int32_t ia, int32_t ib, const collide_step *x,
                                         int measure)
{
    cbody rest_a, rest_b;
    const cbody *A = views_of(w, ia, x->n, &rest_a), *B = views_of(w, ib, x->n, &rest_b);
    int far = narrow_far(w, c, A, B); /* what a measurement in parallel found too: its flags are as then */
    if (measure) narrow_measure(w, c, A, B, far);
    return narrow_decide(w, c, ia, ib, x->n, A, B, far, 1);
}

/* Measuring and staging in parallel: the awake contacts in fixed blocks (a block's manifolds
 * cost some 10-25 us), measured, decided and staged at once, each block's rows at its first
 * contact's index in the spare rows (rows.spare: a contact stages one row at most), with its
 * impacts, the bodies its touching contacts ground and its contacts with an event (at its
 * place in rows.late, their counts after them).  The blocks' counts, summed in block order,
 * place the rows, which are copied there: the rows of the serial walk, in its order.
 * rows.color and rows.tord (scratch of the solve, unused until then) hold each block's first
 * row and first impact. */
#define NARROW_BLOCK SOLVER_STAGE_BLOCK

/* Block blk's bodies to ground, contacts with an event, and the counts of both. */
static inline int32_t *narrow_late_ground(const solver_rows *rows, int32_t blk)
{
    return rows->late + 2 * (size_t)blk * NARROW_BLOCK;
}
static inline int32_t *narrow_late_event(const solver_rows *rows, int32_t blk)
{
    return rows->late + 2 * (size_t)rows->cap + (size_t)blk * NARROW_BLOCK;
}
static inline int32_t *narrow_late_counts(const solver_rows *rows, int32_t blk)
{
    return rows->late + 3 * (size_t)rows->cap + 2 * (size_t)blk;
}

/* A decision's events (begin or end) and the bodies it grounds (none for a sensor). */
static inline int32_t narrow_events(uint32_t bits) { return (bits & (ND_BEGIN | ND_END)) != 0; }
static inline int32_t narrow_grounds(const contact *c, uint32_t bits)
{
    if (c->flags & CT_SENSOR) return 0;
    return ((bits & ND_GROUND_A) != 0) + ((bits & ND_GROUND_B) != 0);
}

/* Items are blocks of NARROW_BLOCK awake contacts (with t->stage, in t->handed's order): each
 * measured and decided those that need no order (a contact's decision reads only its own
 * measurement and its bodies' views), in blocks of eight, the common case's wide
 * (narrow_wide.h); with t->stage, staged too, and its bodies' mean index kept for the next
 * step's hand-out. */
static void narrow_measure_decide_blocks(int32_t begin, int32_t end, int32_t worker, void *context)
{
    narrow_task *t = context;
    rg_world *w = t->w;
    const collide_step *x = t->x;
    solver_rows *rows = &w->coll.rows;
    narrow_block nb;
    narrow_wide_stage st;
    int32_t nc, nimp;
    st.x = x;
    st.d.nc = &nc;
    st.d.nimp = &nimp;
    const int32_t active = w->b.n_active;
    for (int32_t item = begin; item < end; item++) {
        int32_t blk = t->stage ? t->handed[item] : item;
        int32_t first = blk * NARROW_BLOCK, last = first + NARROW_BLOCK < t->n ? first + NARROW_BLOCK : t->n;
        int32_t *ground = narrow_late_ground(rows, blk), *event = narrow_late_event(rows, blk);
        int32_t nground = 0, nevent = 0, met = 0;
        int64_t sum = 0;
        nc = nimp = 0;
        if (t->stage) {
            st.d.stage = rows->spare.stage + first;
            st.d.hgt = rows->spare.hgt + first;
            st.d.ab = rows->spare.ab + 2 * (size_t)first;
            st.d.imp = rows->spare.imp + first;
        }
        for (int32_t k0 = first; k0 < last; k0 += NARROW_WIDE_LANES) {
            int32_t k1 = last - k0 > NARROW_WIDE_LANES ? k0 + NARROW_WIDE_LANES : last;
            narrow_block_run(w, t->x, k0, k1, t->wide, &nb, t->stage ? &st : NULL);
            /* the block's bodies, sampled (each eight's first contact's), for narrow_hand */
            if (t->stage && nb.n > 0) {
                if (nb.ia[0] < active) sum += nb.ia[0], met++;
                if (nb.ib[0] < active) sum += nb.ib[0], met++;
            }
            for (int32_t l = 0; l < nb.n; l++) {
                contact *c = nb.c[l];
                uint32_t bits;
                if (nb.done & (1u << l)) {
                    bits = nb.bits[l];
                } else {
                    const cbody *A = nb.in.a[l], *B = nb.in.b[l];
                    int far = narrow_far(w, c, A, B);
                    narrow_measure(w, c, A, B, far);
                    if (narrow_in_order(w, c)) { /* the walk stages all then */
                        t->in_order[worker] = 1;
                        continue;
                    }
                    bits = narrow_decide(w, c, nb.ia[l], nb.ib[l], x->n, A, B, far, 0);
                }
                c->decided = bits;
                if (bits & ND_SENSOR) t->sensed[worker] = 1;
                if (!t->stage) continue;
                if (narrow_events(bits)) event[nevent++] = nb.id[l];
                if (narrow_grounds(c, bits)) {
                    if (bits & ND_GROUND_A) ground[nground++] = nb.ia[l];
                    if (bits & ND_GROUND_B) ground[nground++] = nb.ib[l];
                }
                if ((bits & ND_STAGE) && !st.staged) narrow_stage_row(w, x, &st.d, nb.id[l], nb.ia[l], nb.ib[l]);
            }
        }
        if (!t->stage) continue;
        rows->color[blk] = nc;
        rows->tord[blk] = nimp;
        narrow_late_counts(rows, blk)[0] = nground;
        narrow_late_counts(rows, blk)[1] = nevent;
        rows->mean[blk] = met > 0 ? (int32_t)(sum / met) : -1;
    }
}

/* Items are blocks, in t->handed's order (a block's rows are copied by the worker that staged
 * them, most likely): each copies its rows from the spare rows to their places (rows.color and
 * rows.tord hold every block's first row and impact, and one past the last block's). */
static void narrow_place_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const narrow_task *t = context;
    solver_rows *rows = &t->w->coll.rows;
    const solver_dest *s = &rows->spare;
    (void)worker;
    for (int32_t item = begin; item < end; item++) {
        int32_t blk = t->handed[item];
        size_t from = (size_t)blk * NARROW_BLOCK, to = (size_t)rows->color[blk];
        size_t n = (size_t)(rows->color[blk + 1] - rows->color[blk]);
        memcpy(rows->stage + to, s->stage + from, n * sizeof *rows->stage);
        memcpy(rows->hgt + to, s->hgt + from, n * sizeof *rows->hgt);
        memcpy(rows->ab + 2 * to, s->ab + 2 * from, 2 * n * sizeof *rows->ab);
        int32_t *imp = rows->imp + rows->tord[blk];
        for (int32_t k = 0; k < rows->tord[blk + 1] - rows->tord[blk]; k++)
            imp[k] = s->imp[from + (size_t)k] + (int32_t)to;
    }
}

/* The order in which the staging's tasks take the blocks (rows.handed): the stages before
 * it (the integration, the views) give each worker a part of the bodies in dense order, and a
 * task system's workers most likely take the parts of a task in the same order (the pool's
 * thread k starts on part k).  A block reads its contacts' bodies' views: handed out in the
 * part where most of those bodies lie (by their mean dense index in the last step with
 * workers), its views are most likely in the cache of the core that takes it, not the
 * other's.  The contacts of a settled scene keep their order and their blocks nearly all
 * their bodies from step to step; a block with no mean yet goes by its place.  Which worker
 * runs which block changes no result. */
static void narrow_hand(rg_world *w, narrow_task *t, int32_t blocks, int32_t workers)
{
    solver_rows *rows = &w->coll.rows;
    int32_t count[RG_MAX_WORKERS + 1] = { 0 };
    int64_t active = w->b.n_active > 0 ? w->b.n_active : 1;
    /* a counting sort by part, stable: each part's blocks in block order */
    for (int32_t blk = 0; blk < blocks; blk++) {
        int32_t m = blk < rows->means ? rows->mean[blk] : -1;
        int32_t part = m >= 0 ? (int32_t)(m * (int64_t)workers / active) : (int32_t)((int64_t)blk * workers / blocks);
        rows->handed[blk] = part < workers ? part : workers - 1; /* the part, for now */
        count[rows->handed[blk] + 1]++;
    }
    for (int32_t k = 0; k < workers; k++) count[k + 1] += count[k];
    /* the parts go into rows.mean's place; the means are written again by the tasks */
    for (int32_t blk = 0; blk < blocks; blk++) rows->mean[blk] = rows->handed[blk];
    for (int32_t blk = 0; blk < blocks; blk++) rows->handed[count[rows->mean[blk]]++] = blk;
    rows->means = blocks;
    t->handed = rows->handed;
}

/* Places the rows of the first t->n awake contacts, all staged in parallel. */
static void narrow_place(rg_world *w, narrow_task *t)
{
    solver_rows *rows = &w->coll.rows;
    collide_step *x = t->x;
    int32_t blocks = (t->n + NARROW_BLOCK - 1) / NARROW_BLOCK;
    int32_t row = 0, imp = 0;
    for (int32_t blk = 0; blk < blocks; blk++) {
        int32_t r = rows->color[blk], m = rows->tord[blk];
        rows->color[blk] = row;
        rows->tord[blk] = imp;
        row += r;
        imp += m;
    }
    rows->color[blocks] = row; /* (blocks < cap: a block holds 256 contacts of cap) */
    rows->tord[blocks] = imp;
    task_for(w, narrow_place_range, blocks, 1, t);
    x->nc = row;
    x->nimp = imp;
    x->nblock = blocks;
}

/* The commits of a step in which nothing can wake, the rows staged already, as narrow_run's
 * walk would make them: the grounded flags and the events from the blocks' lists (the events
 * in contact order), then the islands, joined in contact order. */
static void narrow_commit_late(rg_world *w, collide_step *x)
{
    contact_store *cs = &w->coll.contacts;
    const solver_rows *rows = &w->coll.rows;
    uint32_t *cflags = w->b.cflags;
    for (int32_t blk = 0; blk < x->nblock; blk++) {
        const int32_t *ground = narrow_late_ground(rows, blk);
        for (int32_t k = 0; k < narrow_late_counts(rows, blk)[0]; k++) cflags[ground[k]] |= CF_GROUNDED;
    }
    for (int32_t blk = 0; blk < x->nblock; blk++) {
        const int32_t *event = narrow_late_event(rows, blk);
        for (int32_t k = 0; k < narrow_late_counts(rows, blk)[1]; k++) {
            const contact *c = &cs->c[event[k]];
            narrow_events_of(w, c, c->decided);
        }
    }
    if (!x->unite) return;
    /* touching or solved, as narrow_commit joins them */
    for (int32_t k = 0; k < cs->n_awake; k++) {
        const contact *c = &cs->c[cs->awake[k]];
        if (((c->decided & ND_NOW) || (c->flags & CT_SOLVE)) && !(c->flags & CT_SENSOR))
            narrow_unite(w, c, x, body_dense(w, c->sa), body_dense(w, c->sb));
    }
}

void narrow_press(rg_world *w, collide_step *x)
{
    const solver_constraint *con = w->coll.rows.stage;
    int32_t left = x->pressed;
    for (int32_t k = x->press0; k < x->press1 && left > 0; k++) {
        int32_t id = con[k].cid;
        contact *c = &w->coll.contacts.c[id];
        if (!(c->flags & CT_PRESSED)) continue;
        left--;
        c->flags = (c->flags & ~CT_PRESSED) | CT_TOUCHING;
        c->depth = rg_max(-c->s0, 0);
        c->speed = rg_max(-c->vn0, 0);
        int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb);
        cbody rest_a, rest_b;
        const cbody *A = views_of(w, ia, x->nv, &rest_a), *B = views_of(w, ib, x->nv, &rest_b);
        /* a body the step woke has no view (x->nv, not the restage's x->n): awake now, it
         * feels its gravity */
        const body_store *b = &w->b;
        if (ia >= x->nv) rest_a.gs = b->type[ia] == RG_BODY_DYNAMIC ? b->gscale[ia] : 0;
        if (ib >= x->nv) rest_b.gs = b->type[ib] == RG_BODY_DYNAMIC ? b->gscale[ib] : 0;
        /* solved, so its islands are joined already, and its bodies awake */
        narrow_commit(w, id, ia, ib, x, ND_BEGIN | ND_NOW | narrow_grounded(w, c, A, B), NULL, 0, NULL);
    }
}

void narrow_unskip(rg_world *w)
{
    contact_store *cs = &w->coll.contacts;
    for (int32_t k = 0; k < cs->n_awake; k++) cs->c[cs->awake[k]].flags &= ~CT_SKIPPED;
}

void narrow_run(rg_world *w, collide_step *x)
{
    contact_store *cs = &w->coll.contacts;
    narrow_task t;
    t.w = w;
    t.x = x;
    /* the wide code knows v dt only (narrow_decide's integrator term) */
    t.wide = RG_AVX2_PATHS && narrow_wide_ready(w) && !(w->coll.offk > 0);
    int32_t measured = cs->n_awake, workers = task_workers(w), in_order = 0;
    /* One thread and no body asleep (so nothing wakes, and no commit changes what a later
     * decision reads): the contacts are measured, decided and committed in the one walk
     * below, block by block, the same work as a pass of its own before it. */
    if (workers < 2 && w->b.n_moving == w->b.n_active) measured = 0;
    for (int32_t k = 0; k < workers; k++) t.in_order[k] = t.sensed[k] = 0;
    t.n = measured;
    /* with workers, the rows are staged in parallel too (the spare rows are laid out on the
     * first such step; where the allocator fails, the walk below stages them) */
    t.stage = workers > 1 && measured > 0 && solver_rows_spare(&w->coll.rows, &w->mem);
    t.handed = NULL;
    if (t.stage) narrow_hand(w, &t, (measured + NARROW_BLOCK - 1) / NARROW_BLOCK, workers);
    task_for(w, narrow_measure_decide_blocks, (measured + NARROW_BLOCK - 1) / NARROW_BLOCK, 1, &t);
    for (int32_t k = 0; k < workers; k++) {
        in_order |= t.in_order[k];
        x->sensed |= t.sensed[k];
    }
    /* without a contact decided in order, the rows staged in parallel are those the walk
     * below stages on one thread, in the same order: they are placed */
    int serial = in_order || !t.stage;
    solver_dest dest = resolve_rows_dest(&w->coll.rows, x);
    if (!serial) {
        narrow_place(w, &t);
        /* No body asleep: nothing wakes (a static body never does), so the walk below would
         * only commit, and the solve runs that beside its own first part. */
        if (w->b.n_moving == w->b.n_active) {
            x->late = narrow_commit_late;
            return;
        }
    }
    if (measured == 0) {
        /* Measured here, in blocks of eight: with no body asleep nothing wakes, so the
         * contacts stay as many as at the start, and no decision reads what a commit writes
         * (the pre-solve hook, the one caller outside, may change nothing), so a block's wide
         * decisions, taken before its commits, are those a walk one by one takes.  A contact
         * not done wide is measured and decided in its turn.  A block done whole has its rows
         * staged by the wide code too (in lane order, as the commits would stage them), so
         * its commits stage nothing. */
        narrow_block nb;
        narrow_wide_stage st;
        st.x = x;
        st.d = dest;
        const int unite = x->unite;
        for (int32_t k0 = 0; k0 < cs->n_awake; k0 += NARROW_WIDE_LANES) {
            int32_t k1 = cs->n_awake - k0 > NARROW_WIDE_LANES ? k0 + NARROW_WIDE_LANES : cs->n_awake;
            narrow_block_run(w, x, k0, k1, t.wide, &nb, &st);
            for (int32_t l = 0; l < nb.n; l++) {
                contact *c = nb.c[l];
                int32_t ia = nb.ia[l], ib = nb.ib[l];
                uint32_t bits = (nb.done & (1u << l)) ? nb.bits[l] : narrow_decide_here(w, c, ia, ib, x, 1);
                narrow_commit(w, nb.id[l], ia, ib, x, bits, st.staged ? NULL : &dest, unite, NULL);
            }
        }
        return;
    }
    /* waking appends the contacts of the bodies it wakes: they are measured, decided and
     * staged as they come */
    for (int32_t k = 0; k < cs->n_awake; k++) {
        int32_t id = cs->awake[k];
        contact *c = &cs->c[id];
        int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb); /* a wake moves them only after the commit */
        int here = k >= measured || narrow_in_order(w, c);
        uint32_t bits = here ? narrow_decide_here(w, c, ia, ib, x, k >= measured) : c->decided;
        narrow_commit(w, id, ia, ib, x, bits, serial || k >= measured ? &dest : NULL, x->unite, &x->woke);
    }
}
