/* sense.c: sensors touch where the step ends (see sense.h). */
#include "sense.h"

#include "collision.h"
#include "events.h"
#include "state.h"
#include "vec2.h"

/* The manifold of dense bodies ia and ib's shapes where they are now. */
static void sense_manifold(const body_store *b, int32_t ia, int32_t ib, coll_manifold *m)
{
    coll_manifold_of(b->shape[ia], rg_v2(b->x[ia], b->y[ia]), rg_v2(b->hx[ia], b->hy[ia]), b->shape[ib],
                     rg_v2(b->x[ib], b->y[ib]), rg_v2(b->hx[ib], b->hy[ib]), m);
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
