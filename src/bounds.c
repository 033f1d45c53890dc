/* bounds.c: the range guard of the step, and the list of the bodies it stopped.
 *
 * The accepted ranges keep one step's arithmetic finite from any state in range (forces up
 * to RG_MAX_FORCE on RG_MIN_MASS over RG_MAX_DT give speeds near 1e25 m/s, far inside the
 * float range), but nothing keeps a scene with forces far beyond its scale inside them over
 * many steps: a stiff spring on a light body gains speed every step, and RK4's stages can
 * overflow a damping term (1e9 N s/m times 1e25 m/s) within one.  The guard ends such a
 * body's run at the edge of the range, so the next step starts in range again, and says
 * which body it stopped; the collide stage then sees positions and speeds in range only. */
#include "bounds.h"
#include "dispatch.h"
#include "error.h"
#include "arg.h"
#include "query.h"
#include "state.h"
#include "task.h"
#include "vec2.h"

static rg_real bounds_clamp(rg_real v, rg_real start, rg_real lim)
{
    if (v - v != 0) return start; /* inf or NaN */
    return v > lim ? lim : v < -lim ? -lim : v;
}

void bounds_begin(rg_world *w)
{
    body_store *b = &w->b;
    if (!w->stopped_any) return;
    for (int32_t i = 0; i < b->count; i++) b->flags[i] &= ~BODY_F_STOPPED;
    w->stopped_any = 0;
}

typedef struct bounds_task {
    rg_world *w;
    const rg_real *x0, *y0;
    int32_t stopped[RG_MAX_WORKERS]; /* the worker stopped a body */
} bounds_task;

/* Bodies [i0, i1) of a block with a body out of range: each out stopped. */
static void bounds_stop(bounds_task *t, int32_t worker, int32_t i0, int32_t i1)
{
    body_store *b = &t->w->b;
    const rg_real c = (rg_real)RG_MAX_COORD;
    for (int32_t i = i0; i < i1; i++) {
        if (!bounds_out(b->x[i], b->y[i], b->vx[i], b->vy[i])) continue;
        /* From a start in range Euler cannot overflow (see above), so a non-finite
         * coordinate without a kept start is out of reach; 0 keeps it defined. */
        b->x[i] = bounds_clamp(b->x[i], t->x0 != NULL ? t->x0[i] : 0, c);
        b->y[i] = bounds_clamp(b->y[i], t->y0 != NULL ? t->y0[i] : 0, c);
        b->vx[i] = b->vy[i] = 0;
        b->ax[i] = b->ay[i] = 0;
        b->flags[i] |= BODY_F_STOPPED;
        t->stopped[worker] = 1;
    }
}

/* Bodies per test of a block: the test alone, without a branch, vectorises; a block that
 * holds a body out of range (almost never) is walked again body by body. */
#define BOUNDS_BLOCK 64

/* Active bodies [begin, end): each changes only its own state.  The test in either vector
 * width (dispatch.h). */
DISPATCH static void bounds_range(int32_t begin, int32_t end, int32_t worker, void *context)
{
    bounds_task *t = context;
    body_store *b = &t->w->b;
    const rg_real *x = b->x, *y = b->y, *vx = b->vx, *vy = b->vy;
    int32_t i0 = begin;
    for (; end - i0 >= BOUNDS_BLOCK; i0 += BOUNDS_BLOCK) {
        int32_t out = 0;
        for (int32_t j = 0; j < BOUNDS_BLOCK; j++) out |= bounds_out(x[i0 + j], y[i0 + j], vx[i0 + j], vy[i0 + j]);
        if (out) bounds_stop(t, worker, i0, i0 + BOUNDS_BLOCK);
    }
    if (i0 < end) bounds_stop(t, worker, i0, end);
}

/* Bodies per range: the test costs about a nanosecond. */
#define BOUNDS_RANGE 2048

void bounds_guard(rg_world *w, const rg_real *x0, const rg_real *y0)
{
    bounds_task t;
    int32_t workers = task_workers(w);
    t.w = w;
    t.x0 = x0;
    t.y0 = y0;
    for (int32_t k = 0; k < workers; k++) t.stopped[k] = 0;
    task_for(w, bounds_range, w->b.n_active, BOUNDS_RANGE, &t);
    for (int32_t k = 0; k < workers; k++) w->stopped_any |= t.stopped[k];
}

RG_API int32_t rg_world_get_stopped(const rg_world *world, rg_body *out, int32_t capacity)
{
    ERROR_BEGIN(world);
    ARG_BUFFER(world, out, capacity);
    query_handles q;
    q.out = out;
    q.cap = capacity;
    q.count = 0;
    const body_store *b = &world->b;
    if (world->stopped_any)
        for (int32_t i = 0; i < b->n_moving; i++)
            if (b->flags[i] & BODY_F_STOPPED) query_keep(&q, pool_handle(&world->body_pool, b->slot[i]));
    return query_sorted(&q);
}
