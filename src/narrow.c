/* narrow.c: the narrowphase (see narrow.h). */
#include "body.h"
#include "collision.h"
#include "events.h"
#include "island.h"
#include "narrow.h"
#include "pairs.h"
#include "resolve.h"
#include "state.h"
#include "task.h"
#include "vec2.h"

#define SPECULATIVE      RG_R(4)    /* solve pairs predicted within SPECULATIVE * slop */
#define COS45            RG_R(0.70710678)

void narrow_layout(mem_layout *l, narrow_state *s, int32_t n)
{
    s->cb = mem_take(l, (size_t)n, sizeof(cbody));
    s->sx0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->sy0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->svx0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->svy0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->adense = mem_take(l, (size_t)n, sizeof(int32_t));
    s->refresh = mem_take(l, (size_t)n, sizeof(uint8_t));
}

void narrow_record_start(rg_world *w)
{
    collide_world *cw = &w->coll;
    narrow_state *ns = &cw->narrow;
    if (cw->shape_count == 0) return;
    const broadphase *bp = &cw->bp;
    const body_store *b = &w->b;
    for (int32_t k = 0; k < bp->n_active; k++) {
        int32_t i = body_dense(w, bp->active[k]);
        ns->adense[k] = i;
        ns->sx0[k] = b->x[i];
        ns->sy0[k] = b->y[i];
        ns->svx0[k] = b->vx[i];
        ns->svy0[k] = b->vy[i];
    }
}

typedef struct views_task {
    rg_world *w;
    collide_step *x;
    rg_real dt;
} views_task;

/* The fat box upkeep of awake body k (dense i) from its box after integration. */
static inline void narrow_fat_box(const rg_world *w, int32_t k, int32_t i, rg_real dt, rg_real *box,
                                  rg_real *motion)
{
    const narrow_state *ns = &w->coll.narrow;
    const body_store *b = &w->b;
    rg_real x1 = b->x[i], y1 = b->y[i], hx = b->hx[i], hy = b->hy[i];
    rg_real mx = x1 - ns->sx0[k], my = y1 - ns->sy0[k];
    rg_real lx = x1 - hx, ly = y1 - hy, ux = x1 + hx, uy = y1 + hy;
    if (w->coll.continuous) {
        lx = rg_min(lx, lx - mx);
        ly = rg_min(ly, ly - my);
        ux = rg_max(ux, ux - mx);
        uy = rg_max(uy, uy - my);
    }
    box[0] = lx;
    box[1] = ly;
    box[2] = ux;
    box[3] = uy;
    motion[0] = mx;
    motion[1] = my;
    motion[2] = (b->vx[i] - ns->svx0[k]) * dt;
    motion[3] = (b->vy[i] - ns->svy0[k]) * dt;
}

/* Awake bodies [begin, end): views, displacements and whether the fat box must be refreshed
 * (ns->refresh[k]), each body's own. */
static void narrow_views_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const views_task *t = context;
    rg_world *w = t->w;
    collide_world *cw = &w->coll;
    narrow_state *ns = &cw->narrow;
    body_store *b = &w->b;
    cbody *cb = ns->cb;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        int32_t i = ns->adense[k];
        rg_real box[4], mo[4];
        narrow_fat_box(w, k, i, t->dt, box, mo);
        b->dx[i] = mo[0];
        b->dy[i] = mo[1];
        b->cflags[i] &= ~CF_GROUNDED; /* set again by the touching contacts */
        cb[i].sx = ns->sx0[k];
        cb[i].sy = ns->sy0[k];
        cb[i].dx = mo[0];
        cb[i].dy = mo[1];
        cb[i].vx = ns->svx0[k];
        cb[i].vy = ns->svy0[k];
        cb[i].hx = b->hx[i];
        cb[i].hy = b->hy[i];
        cb[i].gs = b->type[i] == RG_BODY_DYNAMIC ? b->gscale[i] : 0;
        cb[i].im = b->inv_mass[i];
        cb[i].kind = b->shape[i];
        cb[i].pad = 0;
        ns->refresh[k] = (uint8_t)!pairs_inside(&cw->bp.e[b->slot[i]], box);
        if (t->x->unite) cw->island.uf[k] = k;
    }
}

/* Bodies per views range. */
#define VIEWS_RANGE 256

void narrow_views(rg_world *w, collide_step *x, rg_real dt)
{
    views_task t = { w, x, dt };
    narrow_state *ns = &w->coll.narrow;
    task_for(w, narrow_views_range, x->na, VIEWS_RANGE, &t);
    /* the broadphase changes in order, on this thread */
    for (int32_t k = 0; k < x->na; k++) {
        if (!ns->refresh[k]) continue;
        int32_t i = ns->adense[k];
        rg_real box[4], mo[4];
        narrow_fat_box(w, k, i, dt, box, mo);
        pairs_refresh_now(w, i, box[0], box[1], box[2], box[3], mo[0], mo[1], mo[2], mo[3]);
    }
}

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

/* The step's view of body i: start position, displacement, velocity, half extents.  Awake
 * bodies come from the per-step cache, the others rest: no displacement, no velocity. */
static inline const cbody *narrow_view(const rg_world *w, int32_t i, int32_t n, cbody *o)
{
    if (i < n) return &w->coll.narrow.cb[i];
    const body_store *b = &w->b;
    o->sx = b->x[i];
    o->sy = b->y[i];
    o->dx = o->dy = o->vx = o->vy = 0;
    o->hx = b->hx[i];
    o->hy = b->hy[i];
    o->gs = o->im = 0;
    o->kind = b->shape[i];
    return o;
}

/* Whether a pair that is not touching is too far apart for the narrowphase below to solve
 * it or find it touching, so it can be skipped with the same result.  The gap G between the
 * two boxes at the start bounds every separation that test takes from below: the manifold's
 * (a circle lies in its box) unless a box grazes (then the separation is the gap along one
 * axis, within slop of zero: excluded), and a time of impact needs |r| >= G.  The test solves
 * when s0 - reach < SPECULATIVE * slop with reach <= |dA| + |dB| (1-norms bound both), and
 * finds touching only when s0 <= |r|.  The margin covers the rounding of the exact tests:
 * slop, and a few ulps of the coordinates. */
static inline int narrow_far_apart(const cbody *A, const cbody *B, int32_t ka, int32_t kb, rg_real slop)
{
    rg_real gx = rg_fabs(B->sx - A->sx) - (A->hx + B->hx);
    rg_real gy = rg_fabs(B->sy - A->sy) - (A->hy + B->hy);
    rg_real reach = rg_fabs(A->dx) + rg_fabs(A->dy) + rg_fabs(B->dx) + rg_fabs(B->dy);
    rg_real ulps = (rg_fabs(A->sx) + rg_fabs(A->sy) + rg_fabs(B->sx) + rg_fabs(B->sy) + reach +
                    A->hx + A->hy + B->hx + B->hy) * (64 * RG_EPSILON);
    rg_real need = reach + (SPECULATIVE + 1) * slop + ulps;
    if (!(rg_max(gx, gy) >= need)) return 0; /* also NaN */
    /* a box may graze along an axis whose gap is within slop of zero */
    if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) return 1;
    return rg_fabs(gx) > slop && rg_fabs(gy) > slop;
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
        w->locked = 1;
        int32_t keep = w->pre_solve(pool_handle(&w->body_pool, c->sa), pool_handle(&w->body_pool, c->sb),
                                    rg_v2(c->nx, c->ny), s0, w->pre_solve_user);
        w->locked = 0;
        if (!keep) return 1;
    }
    return 0;
}

typedef struct narrow_task {
    rg_world *w;
    const collide_step *x;
} narrow_task;

/* The measurement of contact id (the broadphase keeps only pairs whose fat boxes overlap):
 * the manifold at the start of the step or at the time of impact.  It reads the step's views
 * and writes only the contact's own fields, so the contacts are measured in parallel ranges
 * (narrow_run) before the rest runs in order.  A pair far apart is left to narrow_one, which
 * finds it so again.  Otherwise: CT_ACTIVE when the pair meets within the step, with its
 * normal, point and start separation in nx, ny, px, py, s0. */
static void narrow_measure(const rg_world *w, contact *c, const collide_step *x)
{
    const collide_world *cw = &w->coll;
    int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb);
    cbody rest_a, rest_b;
    const cbody *A = narrow_view(w, ia, x->n, &rest_a), *B = narrow_view(w, ib, x->n, &rest_b);
    int32_t ka = A->kind, kb = B->kind;
    rg_vec2 ha = rg_v2(A->hx, A->hy), hb = rg_v2(B->hx, B->hy);
    rg_vec2 r = rg_v2(B->dx - A->dx, B->dy - A->dy); /* b's motion relative to a over the step */
    if (cw->continuous && !(c->flags & CT_TOUCHING) && narrow_far_apart(A, B, ka, kb, cw->slop)) return;
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
        } else {
            coll_contact(ka, rg_v2(A->sx, A->sy), ha, kb, rg_v2(B->sx, B->sy), hb, r, cw->slop, &m);
            s0 = -m.depth;
        }
        /* apart at the start and fast (moving more than half the smaller shape): the time
         * of impact instead */
        rg_real size = rg_min(rg_min(ha.x, ha.y), rg_min(hb.x, hb.y));
        if (s0 > cw->slop && !(r.x * r.x + r.y * r.y <= RG_R(0.25) * size * size)) {
            rg_real t;
            if (coll_sweep(ka, rg_v2(A->sx, A->sy), ha, kb, rg_v2(B->sx, B->sy), hb, r, &t, &m))
                s0 = t > 0 ? -t * rg_v2_dot(r, m.normal) : -m.depth;
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

static void narrow_measure_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const narrow_task *t = context;
    contact_store *cs = &t->w->coll.contacts;
    (void)worker;
    for (int32_t k = begin; k < end; k++) narrow_measure(t->w, &cs->c[cs->awake[k]], t->x);
}

/* Updates contact id from its measurement: touching state and events, grounded flags,
 * islands, waking, and the solver row. */
static void narrow_one(rg_world *w, int32_t id, collide_step *x)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    body_store *b = &w->b;
    contact *c = &cs->c[id];
    int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb);
    cbody rest_a, rest_b;
    const cbody *A = narrow_view(w, ia, x->n, &rest_a), *B = narrow_view(w, ib, x->n, &rest_b);
    rg_vec2 r = rg_v2(B->dx - A->dx, B->dy - A->dy); /* b's motion relative to a over the step */
    if (cw->continuous && !(c->flags & CT_TOUCHING) && narrow_far_apart(A, B, A->kind, B->kind, cw->slop)) {
        /* what the full test would conclude: not solved, not touching, apart */
        c->flags &= ~(CT_SOLVE | CT_CLOSING | CT_PASS);
        c->pn = c->pt = 0;
        return;
    }
    int active = (c->flags & CT_ACTIVE) != 0;
    rg_real s0 = c->s0;
    c->flags &= ~CT_ACTIVE;
    uint32_t was = c->flags & CT_TOUCHING, now = 0;
    c->flags &= ~(CT_SOLVE | CT_CLOSING);
    if (!active) c->flags &= ~CT_PASS; /* no impact within the step: apart */
    if (active) {
        rg_real nx = c->nx, ny = c->ny;
        rg_real vn0 = (B->vx - A->vx) * nx + (B->vy - A->vy) * ny;
        rg_real d = s0 + r.x * nx + r.y * ny; /* predicted separation */
        /* touching: the step ends with the pair in contact (the free motion closes the gap,
         * which the solver then holds); a slop of hysteresis keeps resting pairs steady */
        if (d <= 0 || (was && d < cw->slop)) now = CT_TOUCHING;
        c->vn0 = vn0;
        if (d < 0) c->flags |= CT_CLOSING;
        /* solved when the pair could close within the step: not only by the free motion
         * (d), but also when the solver stops either body (an impact below it) while the
         * other moves on, so each body's own motion toward the other counts */
        rg_real reach = rg_fabs(A->dx * nx + A->dy * ny) + rg_fabs(B->dx * nx + B->dy * ny);
        int solve = !(c->flags & CT_SENSOR) && s0 - reach < SPECULATIVE * cw->slop && rg_finite(s0) &&
                    rg_finite(vn0);
        /* one-way shapes, pass-through and the pre-solve hook may skip the pair this step */
        if (((c->flags & (CT_ONEWAY | CT_PASS)) || w->pre_solve != NULL) &&
            narrow_skip(w, c, ia, ib, A, B, s0, d, was, now != 0 || solve)) {
            now = 0;
            solve = 0;
            c->flags &= ~CT_CLOSING;
        }
        if (solve) {
            rg_real ima = A->im, imb = B->im;
            if (ima + imb > 0) {
                c->flags |= CT_SOLVE;
                /* An impact: the free motion closes the gap of a pair that was apart, at
                 * the fraction toi of the step (the solve decides whether to time it).  A
                 * pair in contact (touching after the last step, or overlapping) has toi 0:
                 * it may carry weight or pass on an impulse at any moment of the step.  A
                 * pair apart that the free motion does not close has toi -1. */
                rg_real toi = was || s0 <= 0 ? 0 : -1;
                if (d < 0) toi = s0 > 0 && !was ? s0 / (s0 - d) : 0;
                c->toi = toi;
                resolve_stage(w, x, id, ia, ib, ima, imb);
            }
        }
    }
    if (!(c->flags & CT_SOLVE)) c->pn = c->pt = 0;
    if (now != was) {
        c->flags ^= CT_TOUCHING;
        if (now) {
            c->depth = rg_max(-c->s0, 0);
            c->speed = rg_max(-c->vn0, 0);
            cs->n_touching++;
            events_emit(w, c, RG_CONTACT_BEGIN);
        } else {
            cs->n_touching--;
            events_emit(w, c, RG_CONTACT_END);
        }
    }
    if (c->flags & CT_SENSOR) return;
    if (now) {
        if (A->gs != 0 && narrow_is_ground(w->gravity.x, w->gravity.y, A->gs, -c->nx, -c->ny))
            b->cflags[ia] |= CF_GROUNDED;
        if (B->gs != 0 && narrow_is_ground(w->gravity.x, w->gravity.y, B->gs, c->nx, c->ny))
            b->cflags[ib] |= CF_GROUNDED;
        if (x->unite) {
            int32_t pa = cw->bp.e[c->sa].apos, pb = cw->bp.e[c->sb].apos;
            if (pa >= 0 && pb >= 0 && pa < x->na && pb < x->na && b->type[ia] == RG_BODY_DYNAMIC &&
                b->type[ib] == RG_BODY_DYNAMIC)
                island_unite(cw->island.uf, pa, pb);
        }
    }
    /* a sleeping body (dense index past the awake ones) touched by a pusher wakes */
    if ((now | was) && (ia >= b->n_active || ib >= b->n_active)) {
        int pa_ = body_partition(w, ia), pb_ = body_partition(w, ib);
        if (pa_ == BODY_PART_ASLEEP && pb_ == BODY_PART_ACTIVE && narrow_pusher(b, ib, now != 0)) {
            island_wake(w, c->sa);
            x->woke = 1;
        } else if (pb_ == BODY_PART_ASLEEP && pa_ == BODY_PART_ACTIVE && narrow_pusher(b, ia, now != 0)) {
            island_wake(w, c->sb);
            x->woke = 1;
        }
    }
}

/* Contacts per measuring range: the manifolds cost some 30-100 ns each. */
#define NARROW_RANGE 64

void narrow_run(rg_world *w, collide_step *x)
{
    contact_store *cs = &w->coll.contacts;
    narrow_task t = { w, x };
    int32_t measured = cs->n_awake;
    task_for(w, narrow_measure_range, measured, NARROW_RANGE, &t);
    /* waking appends the contacts of the bodies it wakes: they are measured as they come */
    for (int32_t k = 0; k < cs->n_awake; k++) {
        if (k >= measured) narrow_measure(w, &cs->c[cs->awake[k]], x);
        narrow_one(w, cs->awake[k], x);
    }
}
