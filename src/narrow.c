/* narrow.c: the narrowphase (see narrow.h). */
#include "body.h"
#include "collision.h"
#include "events.h"
#include "island.h"
#include "narrow.h"
#include "pairs.h"
#include "resolve.h"
#include "state.h"
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

void narrow_views(rg_world *w, collide_step *x, rg_real dt)
{
    collide_world *cw = &w->coll;
    narrow_state *ns = &cw->narrow;
    body_store *b = &w->b;
    cbody *cb = ns->cb;
    int32_t na = x->na;
    for (int32_t k = 0; k < na; k++) {
        int32_t i = ns->adense[k];
        rg_real x1 = b->x[i], y1 = b->y[i], hx = b->hx[i], hy = b->hy[i];
        rg_real mx = x1 - ns->sx0[k], my = y1 - ns->sy0[k];
        b->dx[i] = mx;
        b->dy[i] = my;
        b->cflags[i] &= ~CF_GROUNDED; /* set again by the touching contacts */
        cb[i].sx = ns->sx0[k];
        cb[i].sy = ns->sy0[k];
        cb[i].dx = mx;
        cb[i].dy = my;
        cb[i].vx = ns->svx0[k];
        cb[i].vy = ns->svy0[k];
        cb[i].hx = hx;
        cb[i].hy = hy;
        cb[i].gs = b->type[i] == RG_BODY_DYNAMIC ? b->gscale[i] : 0;
        cb[i].im = b->inv_mass[i];
        cb[i].kind = b->shape[i];
        cb[i].pad = 0;
        rg_real lx = x1 - hx, ly = y1 - hy, ux = x1 + hx, uy = y1 + hy;
        if (cw->continuous) {
            lx = rg_min(lx, lx - mx);
            ly = rg_min(ly, ly - my);
            ux = rg_max(ux, ux - mx);
            uy = rg_max(uy, uy - my);
        }
        pairs_refresh(w, &cw->bp.e[b->slot[i]], i, lx, ly, ux, uy, mx, my, (b->vx[i] - ns->svx0[k]) * dt,
                      (b->vy[i] - ns->svy0[k]) * dt);
    }
    if (x->unite)
        for (int32_t k = 0; k < na; k++) cw->island.uf[k] = k;
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

/* Whether one-way body i (any body: two-way ones always block) blocks the other body of a
 * contact beginning with normal (nx, ny) from i toward the other and start separation s0. */
static inline int narrow_one_way_blocks(const body_store *b, int32_t i, rg_real nx, rg_real ny,
                                        rg_real s0, rg_real slop)
{
    rg_real ox = b->owx[i], oy = b->owy[i];
    if (ox == 0 && oy == 0) return 1;
    return nx * ox + ny * oy > 0 && s0 >= -slop;
}

/* Whether the pair is skipped (neither solved nor touching) this step: it is passing through
 * (rg_body_pass_through, or a one-way body it met from the wrong side or inside, until a
 * step ends with the shapes apart, d > 0), or the pre-solve hook says so.  `candidate`: the
 * pair would be solved or touching.  A touching one-way contact keeps blocking. */
static int narrow_skip(rg_world *w, contact *c, int32_t ia, int32_t ib, rg_real s0, rg_real d,
                       uint32_t was, int candidate)
{
    if (c->flags & CT_PASS) {
        if (d > 0) c->flags &= ~CT_PASS; /* apart at the end of this step: collides from the next */
        return 1;
    }
    if (!candidate) return 0;
    if ((c->flags & CT_ONEWAY) && !was) {
        const body_store *b = &w->b;
        rg_real slop = w->coll.slop;
        if (!narrow_one_way_blocks(b, ia, c->nx, c->ny, s0, slop) ||
            !narrow_one_way_blocks(b, ib, -c->nx, -c->ny, s0, slop)) {
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

/* Updates contact id from the step's motion (the broadphase keeps only pairs whose fat
 * boxes overlap): manifold at the start of the step or at the time of impact, touching
 * state and events, grounded flags, islands, waking, and the solver row. */
static void narrow_one(rg_world *w, int32_t id, collide_step *x)
{
    collide_world *cw = &w->coll;
    contact_store *cs = &cw->contacts;
    body_store *b = &w->b;
    contact *c = &cs->c[id];
    int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb);
    cbody rest_a, rest_b;
    const cbody *A = narrow_view(w, ia, x->n, &rest_a), *B = narrow_view(w, ib, x->n, &rest_b);
    int32_t ka = A->kind, kb = B->kind;
    rg_vec2 ha = rg_v2(A->hx, A->hy), hb = rg_v2(B->hx, B->hy);
    rg_vec2 r = rg_v2(B->dx - A->dx, B->dy - A->dy); /* b's motion relative to a over the step */
    if (cw->continuous && !(c->flags & CT_TOUCHING) && narrow_far_apart(A, B, ka, kb, cw->slop)) {
        /* what the full test below would conclude: not solved, not touching, apart */
        c->flags &= ~(CT_SOLVE | CT_CLOSING | CT_PASS);
        c->pn = c->pt = 0;
        return;
    }
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
    uint32_t was = c->flags & CT_TOUCHING, now = 0;
    c->flags &= ~(CT_SOLVE | CT_CLOSING);
    if (!active) c->flags &= ~CT_PASS; /* no impact within the step: apart */
    if (active) {
        rg_real nx = m.normal.x, ny = m.normal.y;
        rg_real vn0 = (B->vx - A->vx) * nx + (B->vy - A->vy) * ny;
        rg_real d = s0 + r.x * nx + r.y * ny; /* predicted separation */
        /* touching: the step ends with the pair in contact (the free motion closes the gap,
         * which the solver then holds); a slop of hysteresis keeps resting pairs steady */
        if (d <= 0 || (was && d < cw->slop)) now = CT_TOUCHING;
        c->nx = nx;
        c->ny = ny;
        c->px = m.point.x;
        c->py = m.point.y;
        c->s0 = s0;
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
            narrow_skip(w, c, ia, ib, s0, d, was, now != 0 || solve)) {
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

void narrow_run(rg_world *w, collide_step *x)
{
    contact_store *cs = &w->coll.contacts;
    for (int32_t k = 0; k < cs->n_awake; k++) narrow_one(w, cs->awake[k], x);
}
