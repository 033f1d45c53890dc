/* bench_v3.c: the benchmark's Box2D v3 engine, through v3's public API only.
 *
 * tools/bench_v3.mk compiles this file twice, each time with a copy of v3 built for one SIMD
 * width (BOX2D_AVX2 or not), into a shared library that exports nothing but
 * bench_v3_engine; tools/bench_v3_load.c opens both in one process.
 *
 * Rotation is locked (motionLocks.angularZ); b2World_Step with 4 substeps (v3's
 * recommendation) unless the run sets another count; v3's contact softness, speculative
 * margin and continuous collision at their defaults.  Sleeping follows the run (each body's
 * default threshold, 0.05 m/s for 0.5 s).  With workers > 1 the world gets v3's own
 * scheduler (workerCount without task callbacks).  Frictions mix as sqrt(a*b) and
 * restitutions as max(a, b), so equal values give the pair's.  Damping per unit mass is
 * linearDamping (v *= 1 / (1 + h * c) per substep).  A body without shapes gets its mass
 * from b2Body_SetMassData.  Memory: a counting allocator (b2SetAllocator) sees every byte
 * v3 takes. */
#define _GNU_SOURCE 1 /* M_PI */
#include <box2d/box2d.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef BOX2D_AVX2
#define V3_BUILD "AVX2"
#define V3_NAME "b2v3-avx2"
#else
#define V3_BUILD "SSE2"
#define V3_NAME "b2v3-sse2"
#endif
#ifndef BENCH_V3_SOURCE
#define BENCH_V3_SOURCE "?"
#endif

/* v3 asks for 32-byte aligned blocks and gives the size back on free. */
static atomic_llong v3_live, v3_peak, v3_calls;

static void *v3_alloc(size_t size, int alignment)
{
    size_t a = alignment > 32 ? (size_t)alignment : 32;
    void *p = aligned_alloc(a, (size + a - 1) / a * a);
    if (p == NULL) return NULL;
    long long live = atomic_fetch_add(&v3_live, (long long)size) + (long long)size;
    long long peak = atomic_load(&v3_peak);
    while (live > peak && !atomic_compare_exchange_weak(&v3_peak, &peak, live)) {
    }
    atomic_fetch_add(&v3_calls, 1);
    return p;
}

static void v3_free(void *mem, size_t size)
{
    free(mem);
    atomic_fetch_sub(&v3_live, (long long)size);
    atomic_fetch_add(&v3_calls, 1);
}

typedef struct v3_ctx {
    b2WorldId world;
    b2BodyId *dyn;       /* the dynamic bodies, in list order */
    int32_t ndyn;
    int substeps;
    long long live0;     /* v3's bytes before this world */
} v3_ctx;

static void v3_destroy(void *p)
{
    v3_ctx *c = p;
    if (c == NULL) return;
    if (b2World_IsValid(c->world)) b2DestroyWorld(c->world);
    free(c->dyn);
    free(c);
}

static void *v3_create(const bench_scene *s)
{
    for (int32_t i = 0; i < s->nbodies; i++)
        if (s->bodies[i].nx != 0 || s->bodies[i].ny != 0) return NULL; /* no one-way shapes */
    if (s->variant == BENCH_PRE_SOLVE) return NULL;
    static int allocator_set;
    if (!allocator_set) {
        b2SetAllocator(v3_alloc, v3_free);
        allocator_set = 1;
    }
    v3_ctx *c = calloc(1, sizeof *c);
    if (c == NULL) return NULL;
    c->live0 = atomic_load(&v3_live);
    c->dyn = malloc((size_t)(s->ndynamic > 0 ? s->ndynamic : 1) * sizeof *c->dyn);
    if (c->dyn == NULL) {
        free(c);
        return NULL;
    }
    c->substeps = s->solver_set ? s->solver[0] : 4;
    b2WorldDef wd = b2DefaultWorldDef();
    wd.gravity = (b2Vec2){ (float)s->gx, (float)s->gy };
    wd.enableSleep = s->sleep != 0;
    wd.workerCount = s->workers > 1 ? s->workers : 1;
    c->world = b2CreateWorld(&wd);
    int sensors = 0;
    for (int32_t i = 0; i < s->nbodies; i++) sensors |= s->bodies[i].sensor;
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body *bb = &s->bodies[i];
        int dyn = bb->type == BENCH_DYNAMIC;
        b2BodyDef bd = b2DefaultBodyDef();
        bd.type = dyn ? b2_dynamicBody : b2_staticBody;
        bd.position = (b2Pos){ (float)bb->x, (float)bb->y };
        bd.motionLocks.angularZ = true;
        if (dyn) {
            bd.linearVelocity = (b2Vec2){ (float)bb->vx, (float)bb->vy };
            bd.linearDamping = (float)s->damping;
        }
        b2BodyId body = b2CreateBody(c->world, &bd);
        if (bb->shape != BENCH_SHAPE_NONE) {
            b2ShapeDef sd = b2DefaultShapeDef();
            double area = bb->shape == BENCH_SHAPE_CIRCLE ? M_PI * bb->a * bb->a : 4 * bb->a * bb->b;
            sd.density = dyn ? (float)(bb->mass / area) : 0.0f;
            sd.material.friction = (float)s->friction;
            sd.material.restitution = (float)s->restitution;
            sd.isSensor = bb->sensor != 0;
            sd.enableSensorEvents = sensors != 0;
            if (bb->shape == BENCH_SHAPE_CIRCLE) {
                b2Circle circle = { { 0.0f, 0.0f }, (float)bb->a };
                b2CreateCircleShape(body, &sd, &circle);
            } else {
                b2Polygon box = b2MakeBox((float)bb->a, (float)bb->b);
                b2CreatePolygonShape(body, &sd, &box);
            }
        } else if (dyn) {
            b2MassData md = { (float)bb->mass, { 0.0f, 0.0f }, 0.0f };
            b2Body_SetMassData(body, md);
        }
        if (dyn) c->dyn[c->ndyn++] = body;
    }
    return c;
}

static void v3_step(void *p, double dt)
{
    v3_ctx *c = p;
    b2World_Step(c->world, (float)dt, c->substeps);
}

static void v3_force(void *p, int32_t k, double fx, double fy)
{
    v3_ctx *c = p;
    b2Body_ApplyForceToCenter(c->dyn[k], (b2Vec2){ (float)fx, (float)fy }, true);
}

static void v3_impulse(void *p, int32_t k, double ix, double iy)
{
    v3_ctx *c = p;
    b2Body_ApplyLinearImpulseToCenter(c->dyn[k], (b2Vec2){ (float)ix, (float)iy }, true);
}

static void v3_read(void *p, float *x, float *y, float *vx, float *vy)
{
    v3_ctx *c = p;
    for (int32_t k = 0; k < c->ndyn; k++) {
        b2Pos q = b2Body_GetPosition(c->dyn[k]);
        b2Vec2 v = b2Body_GetLinearVelocity(c->dyn[k]);
        x[k] = (float)q.x;
        y[k] = (float)q.y;
        vx[k] = v.x;
        vy[k] = v.y;
    }
}

static size_t v3_bytes(void *p, size_t *peak)
{
    const v3_ctx *c = p;
    long long live = atomic_load(&v3_live) - c->live0, top = atomic_load(&v3_peak) - c->live0;
    *peak = top > 0 ? (size_t)top : 0;
    return live > 0 ? (size_t)live : 0;
}

static int64_t v3_alloc_calls(void *p)
{
    (void)p;
    return (int64_t)atomic_load(&v3_calls);
}

static size_t v3_save(void *p, void *buf, size_t cap)
{
    v3_ctx *c = p;
    int size = b2World_Snapshot(c->world, buf, buf != NULL && cap < 0x7fffffff ? (int)cap : 0);
    return size > 0 ? (size_t)size : 0;
}

static int v3_restore(void *p, const void *buf, size_t size)
{
    v3_ctx *c = p;
    return size < 0x7fffffff && b2World_Restore(c->world, buf, (int)size);
}

static uint64_t v3_hash(void *p)
{
    v3_ctx *c = p;
    return b2World_GetStateHash(c->world);
}

static const char *v3_version(void)
{
    static char text[96];
    b2Version v = b2GetVersion();
    snprintf(text, sizeof text, "Box2D %d.%d.%d (%s build of %s)", v.major, v.minor, v.revision,
             V3_BUILD, BENCH_V3_SOURCE);
    return text;
}

__attribute__((visibility("default"))) const bench_engine bench_v3_engine = {
    .name = V3_NAME, .threaded = 1, .create = v3_create, .step = v3_step, .force = v3_force,
    .impulse = v3_impulse, .read = v3_read, .bytes = v3_bytes, .destroy = v3_destroy,
    .alloc_calls = v3_alloc_calls, .version = v3_version,
    .save = v3_save, .restore = v3_restore, .hash = v3_hash,
};
