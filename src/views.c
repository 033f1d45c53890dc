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
    rg_real dt;
} views_task;

/* The fat box upkeep of awake body k (dense i) from its box after integration. */
static inline void views_fat_box(const rg_world *w, int32_t k, int32_t i, rg_real dt, rg_real *box,
                                  rg_real *motion)
{
    const views_state *ns = &w->coll.views;
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
static void views_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    const views_task *t = context;
    rg_world *w = t->w;
    collide_world *cw = &w->coll;
    views_state *ns = &cw->views;
    body_store *b = &w->b;
    cbody *cb = ns->cb;
    (void)worker;
    for (int32_t k = begin; k < end; k++) {
        int32_t i = ns->adense[k];
        rg_real box[4], mo[4];
        views_fat_box(w, k, i, t->dt, box, mo);
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

void views_build(rg_world *w, collide_step *x, rg_real dt)
{
    views_task t = { w, x, dt };
    views_state *ns = &w->coll.views;
    task_for(w, views_range, x->na, VIEWS_RANGE, &t);
    /* the broadphase changes in order, on this thread */
    for (int32_t k = 0; k < x->na; k++) {
        if (!ns->refresh[k]) continue;
        int32_t i = ns->adense[k];
        rg_real box[4], mo[4];
        views_fat_box(w, k, i, dt, box, mo);
        pairs_refresh_now(w, i, box[0], box[1], box[2], box[3], mo[0], mo[1], mo[2], mo[3]);
    }
}

