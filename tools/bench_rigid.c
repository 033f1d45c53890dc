/* bench_rigid.c: the benchmark's rigid engine, through the public API only.
 *
 * Scenes with shapes need the collision API (rg_body_set_circle ...); tools/bench.mk
 * defines RG_BENCH_COLLISION when include/rigid.h declares it, and without it such scenes
 * are reported as not available rather than run without collision.  Likewise
 * RG_BENCH_THREADS when the task system is there (rg_thread_pool_create): a run with
 * workers > 1 then steps with rigid's own pool of that many threads. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "rigid.h"

/* Counts every byte the world holds through rg_world_create_with_allocator. */
typedef struct counting_alloc {
    size_t live, peak;
    int64_t calls;
} counting_alloc;

static void *count_alloc(void *user, void *ptr, size_t old_size, size_t new_size)
{
    counting_alloc *c = user;
    c->calls++;
    if (new_size == 0) {
        free(ptr);
        c->live -= old_size;
        return NULL;
    }
    void *p = realloc(ptr, new_size);
    if (p == NULL) return NULL;
    c->live = c->live - old_size + new_size;
    if (c->live > c->peak) c->peak = c->live;
    return p;
}

#ifdef RG_BENCH_THREADS
#define RIGID_THREADED 1
#else
#define RIGID_THREADED 0
#endif

typedef struct rigid_ctx {
    counting_alloc mem;
    rg_world *w;
#ifdef RG_BENCH_THREADS
    rg_thread_pool *pool;   /* s->workers > 1 */
    rg_task_system tasks;
#endif
    rg_body *dyn;   /* handles of the dynamic bodies, in list order */
    int32_t ndyn;
    rg_body *one_way;      /* the one-way bodies (BENCH_ONE_WAY), whose pairs are counted */
    int32_t none_way;
    int64_t hook_calls;    /* pre-solve calls since the last contacts read (BENCH_PRE_SOLVE) */
} rigid_ctx;

static rg_vec2 v2(double x, double y)
{
    rg_vec2 v;
    v.x = (rg_real)x;
    v.y = (rg_real)y;
    return v;
}

static void rigid_destroy(void *p)
{
    rigid_ctx *c = p;
    if (c == NULL) return;
    rg_world_destroy(c->w);
#ifdef RG_BENCH_THREADS
    if (c->pool != NULL) rg_thread_pool_destroy(c->pool);
#endif
    free(c->dyn);
    free(c->one_way);
    free(c);
}

static int rigid_add_shape(rigid_ctx *c, rg_body h, const bench_body *bb, const bench_scene *s)
{
#ifdef RG_BENCH_COLLISION
    rg_status st = RG_OK;
    if (bb->shape == BENCH_SHAPE_CIRCLE)
        st = rg_body_set_circle(c->w, h, (rg_real)bb->a);
    else
        st = rg_body_set_aabb(c->w, h, (rg_real)bb->a, (rg_real)bb->b);
    /* A pair uses the geometric mean of the two frictions, so each body gets the pair's. */
    if (st == RG_OK) st = rg_body_set_friction(c->w, h, (rg_real)s->friction);
    if (st == RG_OK && s->restitution != 0)
        st = rg_body_set_restitution(c->w, h, (rg_real)s->restitution);
    if (st == RG_OK && bb->sensor) st = rg_body_set_sensor(c->w, h, 1);
    if (st == RG_OK && (bb->nx != 0 || bb->ny != 0)) {
        st = rg_body_set_one_way(c->w, h, v2(bb->nx, bb->ny));
        c->one_way[c->none_way++] = h;
    }
    return st == RG_OK;
#else
    (void)c;
    (void)h;
    (void)bb;
    (void)s;
    return 0;
#endif
}

#ifdef RG_BENCH_COLLISION
/* The pre-solve hook of BENCH_PRE_SOLVE: counts its calls and keeps every pair. */
static int32_t rigid_keep_pair(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user)
{
    (void)a;
    (void)b;
    (void)normal;
    (void)separation;
    ((rigid_ctx *)user)->hook_calls++;
    return 1;
}
#endif

static void *rigid_create(const bench_scene *s)
{
    rigid_ctx *c = calloc(1, sizeof *c);
    if (c == NULL) return NULL;
    c->dyn = malloc((size_t)(s->ndynamic > 0 ? s->ndynamic : 1) * sizeof *c->dyn);
    if (s->variant == BENCH_ONE_WAY) c->one_way = malloc((size_t)s->nbodies * sizeof *c->one_way);
    if (c->dyn == NULL || (s->variant == BENCH_ONE_WAY && c->one_way == NULL) ||
        rg_world_create_with_allocator(count_alloc, &c->mem, &c->w) != RG_OK) {
        rigid_destroy(c);
        return NULL;
    }
    rg_world_set_gravity(c->w, v2(s->gx, s->gy));
    if (rg_world_set_sleeping(c->w, s->sleep) != RG_OK) goto fail;
    if (s->solver_set && rg_world_set_solver_iterations(c->w, s->solver[0], s->solver[1]) != RG_OK)
        goto fail;
#ifdef RG_BENCH_THREADS
    if (s->workers > 1 && (rg_thread_pool_create(s->workers, &c->pool) != RG_OK ||
                           rg_thread_pool_task_system(c->pool, &c->tasks) != RG_OK ||
                           rg_world_set_task_system(c->w, &c->tasks) != RG_OK))
        goto fail;
#else
    if (s->workers > 1) goto fail;
#endif
#ifdef RG_BENCH_COLLISION
    if (s->variant == BENCH_PRE_SOLVE && rg_world_set_pre_solve(c->w, rigid_keep_pair, c) != RG_OK)
        goto fail;
    if ((s->variant == BENCH_VERLET || s->variant == BENCH_RK4) &&
        rg_world_set_integrator(c->w, s->variant == BENCH_RK4 ? RG_INTEGRATOR_RK4 : RG_INTEGRATOR_VELOCITY_VERLET) !=
            RG_OK)
        goto fail;
#else
    if (s->variant != BENCH_PLAIN) goto fail;
#endif
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body *bb = &s->bodies[i];
        int dyn = bb->type == BENCH_DYNAMIC;
        rg_body h;
        if (rg_body_create(c->w, dyn ? RG_BODY_DYNAMIC : RG_BODY_STATIC, (rg_real)bb->mass,
                           v2(bb->x, bb->y), &h) != RG_OK)
            goto fail;
        if (bb->shape != BENCH_SHAPE_NONE && !rigid_add_shape(c, h, bb, s)) goto fail;
        if (dyn) {
            if ((bb->vx != 0 || bb->vy != 0) && rg_body_set_velocity(c->w, h, v2(bb->vx, bb->vy)) != RG_OK)
                goto fail;
            if (s->damping > 0 &&
                rg_body_set_drag(c->w, h, (rg_real)(s->damping * bb->mass), 0) != RG_OK)
                goto fail;
            c->dyn[c->ndyn++] = h;
        }
    }
    return c;
fail:
    rigid_destroy(c);
    return NULL;
}

void *bench_rigid_world(void *ctx) { return ((rigid_ctx *)ctx)->w; }

static void rigid_step(void *p, double dt)
{
    rigid_ctx *c = p;
    rg_world_step(c->w, (rg_real)dt);
}

static void rigid_force(void *p, int32_t k, double fx, double fy)
{
    rigid_ctx *c = p;
    rg_body_apply_force(c->w, c->dyn[k], v2(fx, fy));
}

static void rigid_impulse(void *p, int32_t k, double ix, double iy)
{
    rigid_ctx *c = p;
    rg_body_apply_impulse(c->w, c->dyn[k], v2(ix, iy));
}

static void rigid_read(void *p, float *x, float *y, float *vx, float *vy)
{
    rigid_ctx *c = p;
    for (int32_t k = 0; k < c->ndyn; k++) {
        rg_vec2 q = v2(0, 0), v = v2(0, 0);
        rg_body_get_position(c->w, c->dyn[k], &q);
        rg_body_get_velocity(c->w, c->dyn[k], &v);
        x[k] = (float)q.x;
        y[k] = (float)q.y;
        vx[k] = (float)v.x;
        vy[k] = (float)v.y;
    }
}

static size_t rigid_bytes(void *p, size_t *peak)
{
    const rigid_ctx *c = p;
    *peak = c->mem.peak;
    return c->mem.live;
}

static int64_t rigid_alloc_calls(void *p)
{
    const rigid_ctx *c = p;
    return c->mem.calls;
}

#ifdef RG_DOUBLE
#define RIGID_BUILD "double"
#else
#define RIGID_BUILD "float"
#endif

static void rigid_contacts(void *p, bench_contacts *out)
{
    rigid_ctx *c = p;
    int64_t pairs = 0;
#ifdef RG_BENCH_COLLISION
    out->touching = rg_world_touching_count(c->w);
    for (int32_t k = 0; k < c->none_way; k++) pairs += rg_body_get_contacts(c->w, c->one_way[k], NULL, 0);
#else
    out->touching = 0;
#endif
    out->one_way = (double)pairs;
    out->pre_solve_calls = (double)c->hook_calls;
    c->hook_calls = 0;
}

static size_t rigid_save(void *p, void *buf, size_t cap)
{
    rigid_ctx *c = p;
    size_t size = 0;
    if (rg_world_save(c->w, buf, buf != NULL ? cap : 0, &size) == RG_OK) return size;
    return buf == NULL || size > cap ? size : 0; /* the size query refuses with the size */
}

static int rigid_restore(void *p, const void *buf, size_t size)
{
    rigid_ctx *c = p;
    return rg_world_restore(c->w, buf, size) == RG_OK;
}

static uint64_t rigid_hash(void *p)
{
    rigid_ctx *c = p;
    uint64_t h = 0;
    rg_world_hash(c->w, &h);
    return h;
}

static int rigid_keep(void *p, int slot)
{
    rigid_ctx *c = p;
    return rg_world_save_slot(c->w, slot) == RG_OK;
}

static int rigid_back(void *p, int slot)
{
    rigid_ctx *c = p;
    return rg_world_restore_slot(c->w, slot) == RG_OK;
}

static const char *rigid_version(void)
{
    static char text[48];
    int32_t v = rg_version();
    snprintf(text, sizeof text, "rigid %d.%d.%d (%s)", (int)(v / 10000), (int)(v / 100 % 100),
             (int)(v % 100), RIGID_BUILD);
    return text;
}

const bench_engine bench_rigid_engine = {
    .name = "rigid", .threaded = RIGID_THREADED, .create = rigid_create, .step = rigid_step,
    .force = rigid_force, .impulse = rigid_impulse, .read = rigid_read, .bytes = rigid_bytes,
    .destroy = rigid_destroy, .alloc_calls = rigid_alloc_calls, .version = rigid_version,
    .contacts = rigid_contacts, .save = rigid_save, .restore = rigid_restore, .hash = rigid_hash,
    .keep = rigid_keep, .back = rigid_back,
};
