/* views.h: the collide stage's view of the bodies: where the awake shaped bodies start
 * (before integration), and after it their displacement, velocity and size, one cache line
 * per body for the narrowphase, with the fat boxes refreshed that their swept box left. */
#ifndef RG_VIEWS_H
#define RG_VIEWS_H

#include <stdint.h>

#include "state.h"

/* The scratch arrays for n bodies. */
void views_layout(mem_layout *l, views_state *s, int32_t n);
/* Before integration: remembers where the awake shaped bodies start. */
void views_record_start(struct rg_world *w);
/* After integration: the displacements, the step's view of each awake shaped body, and its
 * fat box refreshed when its swept box left it. */
void views_build(struct rg_world *w, collide_step *x, rg_real dt);
/* After the narrowphase of a step that woke bodies (places x->na .. the broadphase's active
 * count): their dense index and where they start, before the solve moves them (continuous.c's
 * sweep; their start velocity is 0, which nothing past x->na reads). */
void views_woken(struct rg_world *w, const collide_step *x);

/* The step's view of body i: start position, displacement, velocity, half extents.  Awake
 * bodies come from the per-step cache, the others rest: no displacement, no velocity. */
static inline const cbody *views_of(const rg_world *w, int32_t i, int32_t n, cbody *o)
{
    if (i < n) return &w->coll.views.cb[i];
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

#endif
