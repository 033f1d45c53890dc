/* views.c: the step's view of each awake shaped body (start, displacement, velocity,
 * size), and the fat boxes that left their box after integration (see views.h). */
#include "pairs.h"
#include "state.h"
#include "task.h"
#include "vec2.h"
#include "views.h"

void views_layout(mem_layout *l, views_state *s, int32_t n)
{
    s->cb = mem_take(l, (size_t)n, sizeof(cbody));
    s->sx0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->sy0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->svx0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->svy0 = mem_take(l, (size_t)n, sizeof(rg_real));
    s->adense = mem_take(l, (size_t)n, sizeof(int32_t));
    s->refresh = mem_take(l, (size_t)n, sizeof(uint8_t));
}

/* Awake shaped bodies [begin, end) of the broadphase's list: each writes its own start. */
static void views_start_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    rg_world *w = context;
    views_state *ns = &w->coll.views;
    const broadphase *bp = &w->coll.bp;
    const body_store *b = &w->b;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        int32_t i = body_dense(w, bp->active[k]);
        ns->adense[k] = i;
        ns->sx0[k] = b->x[i];
        ns->sy0[k] = b->y[i];
        ns->svx0[k] = b->vx[i];
        ns->svy0[k] = b->vy[i];
    }
}

/* Bodies per range of the cheap per-body passes (a few ns each). */
#define VIEWS_START_RANGE 1024

void views_record_start(rg_world *w)
{
    if (w->coll.shape_count == 0) return;
    task_for(w, views_start_range, w->coll.bp.n_active, VIEWS_START_RANGE, w);
}

typedef struct views_task {
    rg_world *w;
    collide_step *x;
} views_task;

/* The fat box of a body at (x1, y1) with half extents (hx, hy) that moved by (mx, my) this
 * step: its box, swept back over the motion when the collision is continuous. */
static inline void views_box(rg_real x1, rg_real y1, rg_real hx, rg_real hy, rg_real mx, rg_real my,
                             int continuous, rg_real *box)
{
    rg_real lx = x1 - hx, ly = y1 - hy, ux = x1 + hx, uy = y1 + hy;
    if (continuous) {
        lx = rg_min(lx, lx - mx);
        ly = rg_min(ly, ly - my);
        ux = rg_max(ux, ux - mx);
        uy = rg_max(uy, uy - my);
    }
    box[0] = lx;
    box[1] = ly;
    box[2] = ux;
    box[3] = uy;
}

/* Awake bodies [begin, end): views, displacements and whether the fat box must be refreshed
 * (ns->refresh[k]), each body's own. */
static void views_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const views_task *t = context;
    rg_world *w = t->w;
    collide_world *cw = &w->coll;
    views_state *ns = &cw->views;
    body_store *b = &w->b;
    /* the arrays in locals: the stores below cannot move them, so they are read once */
    cbody *cb = ns->cb;
    const int32_t *adense = ns->adense;
    const rg_real *sx0 = ns->sx0, *sy0 = ns->sy0, *svx0 = ns->svx0, *svy0 = ns->svy0;
    const rg_real *x = b->x, *y = b->y, *hx = b->hx, *hy = b->hy;
    const rg_real *gscale = b->gscale, *inv_mass = b->inv_mass;
    const int32_t *type = b->type, *shape = b->shape, *slot = b->slot;
    rg_real *dx = b->dx, *dy = b->dy;
    uint32_t *cflags = b->cflags;
    uint8_t *refresh = ns->refresh;
    int32_t *uf = t->x->unite ? cw->island.uf : NULL;
    const bp_entry *e = cw->bp.e;
    int continuous = cw->continuous;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        int32_t i = adense[k];
        rg_real x1 = x[i], y1 = y[i], h0 = hx[i], h1 = hy[i];
        rg_real mx = x1 - sx0[k], my = y1 - sy0[k], box[4];
        views_box(x1, y1, h0, h1, mx, my, continuous, box);
        dx[i] = mx;
        dy[i] = my;
        cflags[i] &= ~CF_GROUNDED; /* set again by the touching contacts */
        cbody v;
        v.sx = sx0[k];
        v.sy = sy0[k];
        v.dx = mx;
        v.dy = my;
        v.vx = svx0[k];
        v.vy = svy0[k];
        v.hx = h0;
        v.hy = h1;
        v.gs = type[i] == RG_BODY_DYNAMIC ? gscale[i] : 0;
        v.im = inv_mass[i];
        v.kind = shape[i];
        v.pad = 0;
        cb[i] = v;
        refresh[k] = (uint8_t)!pairs_inside(&e[slot[i]], box);
        if (uf != NULL) uf[k] = k;
    }
}

/* Bodies per views range. */
#define VIEWS_RANGE 256

void views_build(rg_world *w, collide_step *x, rg_real dt)
{
    views_task t = { w, x };
    views_state *ns = &w->coll.views;
    const body_store *b = &w->b;
    task_for(w, views_range, x->na, VIEWS_RANGE, &t);
    /* the broadphase changes in order, on this thread */
    for (int32_t k = 0; k < x->na; k++) {
        if (!ns->refresh[k]) continue;
        int32_t i = ns->adense[k];
        rg_real mx = b->x[i] - ns->sx0[k], my = b->y[i] - ns->sy0[k], box[4];
        views_box(b->x[i], b->y[i], b->hx[i], b->hy[i], mx, my, w->coll.continuous, box);
        pairs_refresh_now(w, i, box[0], box[1], box[2], box[3], mx, my, (b->vx[i] - ns->svx0[k]) * dt,
                          (b->vy[i] - ns->svy0[k]) * dt);
    }
}

