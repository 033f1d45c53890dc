/* sense.c: sensors touch where the step ends (see sense.h). */
#include "sense.h"

#include "collision.h"
#include "events.h"
#include "state.h"
#include "vec2.h"
#include "views.h"

/* The manifold of dense bodies ia and ib's shapes where they are now. */
static void sense_manifold(const body_store *b, int32_t ia, int32_t ib, coll_manifold *m)
{
    coll_manifold_of(b->shape[ia], rg_v2(b->x[ia], b->y[ia]), rg_v2(b->hx[ia], b->hy[ia]), b->shape[ib],
                     rg_v2(b->x[ib], b->y[ib]), rg_v2(b->hx[ib], b->hy[ib]), m);
}

/* Whether dense bodies ia and ib's shapes, apart where the step leaves them, met within it:
 * the straight path of their relative motion, from their views' starts (n: the bodies with
 * a view, x->nv) to where they are, crosses the other shape (*m: where it enters).  Only where that
 * motion exceeds half the smaller shape: a slower pair that meets within a step ends it
 * touching, but at a corner grazed in passing. */
static int sense_crossed(const rg_world *w, int32_t ia, int32_t ib, int32_t n, coll_manifold *m)
{
    const body_store *b = &w->b;
    cbody oa, ob;
    const cbody *A = views_of(w, ia, n, &oa), *B = views_of(w, ib, n, &ob);
    rg_vec2 ha = rg_v2(b->hx[ia], b->hy[ia]), hb = rg_v2(b->hx[ib], b->hy[ib]);
    rg_vec2 r = rg_v2((b->x[ib] - B->sx) - (b->x[ia] - A->sx), (b->y[ib] - B->sy) - (b->y[ia] - A->sy));
    rg_real size = rg_min(rg_min(ha.x, ha.y), rg_min(hb.x, hb.y));
    if (!(r.x * r.x + r.y * r.y > RG_R(0.25) * size * size)) return 0;
    rg_real t;
    return coll_sweep(b->shape[ia], rg_v2(A->sx, A->sy), ha, b->shape[ib], rg_v2(B->sx, B->sy), hb, r, &t, m);
}

void sense_run(rg_world *w, const collide_step *x)
{
    if (!x->sensed) return;
    contact_store *cs = &w->coll.contacts;
    const body_store *b = &w->b;
    const rg_real slop = w->coll.slop;
    for (int32_t k = 0; k < cs->n_awake; k++) {
        contact *c = &cs->c[cs->awake[k]];
        if (!(c->flags & CT_SENSOR)) continue;
        int32_t ia = body_dense(w, c->sa), ib = body_dense(w, c->sb);
        coll_manifold m;
        sense_manifold(b, ia, ib, &m);
        rg_real sep = -m.depth; /* NaN: never touching */
        uint32_t was = c->flags & CT_TOUCHING, now = 0;
        if (c->flags & CT_PASS) {
            /* passing through (rg_body_pass_through) until a step ends with the shapes apart */
            if (sep > 0) c->flags &= ~CT_PASS;
        } else if (sep <= 0 || (was && sep < slop)) {
            now = CT_TOUCHING; /* a slop of hysteresis, as the narrowphase keeps for solid pairs */
        } else if (!was && sense_crossed(w, ia, ib, x->nv, &m)) {
            /* crossed within the step (a bullet through a thin trigger): touching for this
             * step, where it entered, and apart from the next */
            now = CT_TOUCHING;
            m.depth = 0;
        }
        /* the end event's normal and point: the shapes as they end the step */
        c->nx = m.normal.x;
        c->ny = m.normal.y;
        c->px = m.point.x;
        c->py = m.point.y;
        if (now == was) continue;
        c->flags ^= CT_TOUCHING;
        if (now) {
            rg_real vn = (b->vx[ib] - b->vx[ia]) * m.normal.x + (b->vy[ib] - b->vy[ia]) * m.normal.y;
            c->depth = rg_max(m.depth, 0);
            c->speed = rg_max(-vn, 0);
            cs->n_touching++;
            events_emit(w, c, RG_CONTACT_BEGIN);
        } else {
            cs->n_touching--;
            events_emit(w, c, RG_CONTACT_END);
        }
    }
}
