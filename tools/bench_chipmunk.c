/* bench_chipmunk.c: the benchmark's Chipmunk 7 engine, through Debian's libchipmunk-dev only.
 *
 * Rotation is locked with an infinite moment of inertia; default iterations (10) unless the
 * run sets others, default spatial index (bounding-box tree), default collision slop.
 * Sleeping as the run says: on, a body sleeps after 0.5 s below Chipmunk's idle speed (its
 * default estimate from gravity); off is Chipmunk's default.  Chipmunk multiplies the two shapes' frictions (and elasticities) of a pair,
 * so each shape gets the square root of the pair's value.  Damping per unit mass is the
 * space's damping, the fraction of velocity kept per second: exp(-c).  Static shapes hang
 * on the space's static body, as Chipmunk's own demos build levels. */
#include <chipmunk/chipmunk.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"

typedef struct chipmunk_ctx {
    cpSpace *space;
    cpBody **dyn;
    int32_t ndyn;
    cpShape **shapes;
    int32_t nshapes;
} chipmunk_ctx;

static void chipmunk_destroy(void *p)
{
    chipmunk_ctx *c = p;
    if (c == NULL) return;
    if (c->space != NULL) cpSpaceFree(c->space);
    for (int32_t i = 0; i < c->nshapes; i++) cpShapeFree(c->shapes[i]);
    for (int32_t i = 0; i < c->ndyn; i++) cpBodyFree(c->dyn[i]);
    free(c->shapes);
    free(c->dyn);
    free(c);
}

static void *chipmunk_create(const bench_scene *s)
{
    if (s->workers > 1) return NULL;
    chipmunk_ctx *c = calloc(1, sizeof *c);
    if (c == NULL) return NULL;
    c->dyn = malloc((size_t)(s->ndynamic > 0 ? s->ndynamic : 1) * sizeof *c->dyn);
    c->shapes = malloc((size_t)(s->nbodies > 0 ? s->nbodies : 1) * sizeof *c->shapes);
    c->space = cpSpaceNew();
    if (c->dyn == NULL || c->shapes == NULL || c->space == NULL) {
        chipmunk_destroy(c);
        return NULL;
    }
    cpSpaceSetGravity(c->space, cpv(s->gx, s->gy));
    if (s->sleep) cpSpaceSetSleepTimeThreshold(c->space, 0.5);
    if (s->solver_set) cpSpaceSetIterations(c->space, s->solver[0]);
    if (s->damping > 0) cpSpaceSetDamping(c->space, exp(-s->damping));
    cpBody *ground = cpSpaceGetStaticBody(c->space);
    double mu = sqrt(s->friction), e = sqrt(s->restitution);
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body *bb = &s->bodies[i];
        cpBody *body;
        cpVect off = cpvzero;
        if (bb->type == BENCH_DYNAMIC) {
            body = cpSpaceAddBody(c->space, cpBodyNew(bb->mass, INFINITY));
            cpBodySetPosition(body, cpv(bb->x, bb->y));
            cpBodySetVelocity(body, cpv(bb->vx, bb->vy));
            c->dyn[c->ndyn++] = body;
        } else {
            body = ground;
            off = cpv(bb->x, bb->y);
        }
        if (bb->shape == BENCH_SHAPE_NONE) continue;
        cpShape *shape;
        if (bb->shape == BENCH_SHAPE_CIRCLE)
            shape = cpCircleShapeNew(body, bb->a, off);
        else
            shape = cpBoxShapeNew2(body, cpBBNew(off.x - bb->a, off.y - bb->b, off.x + bb->a,
                                                 off.y + bb->b), 0);
        cpShapeSetFriction(shape, mu);
        cpShapeSetElasticity(shape, e);
        if (bb->sensor) cpShapeSetSensor(shape, cpTrue);
        cpSpaceAddShape(c->space, shape);
        c->shapes[c->nshapes++] = shape;
    }
    return c;
}

static void chipmunk_step(void *p, double dt)
{
    chipmunk_ctx *c = p;
    cpSpaceStep(c->space, dt);
}

static void chipmunk_force(void *p, int32_t k, double fx, double fy)
{
    chipmunk_ctx *c = p;
    cpBody *b = c->dyn[k];
    cpBodyApplyForceAtWorldPoint(b, cpv(fx, fy), cpBodyGetPosition(b));
}

static void chipmunk_impulse(void *p, int32_t k, double ix, double iy)
{
    chipmunk_ctx *c = p;
    cpBody *b = c->dyn[k];
    cpBodyApplyImpulseAtWorldPoint(b, cpv(ix, iy), cpBodyGetPosition(b));
}

static void chipmunk_read(void *p, float *x, float *y, float *vx, float *vy)
{
    chipmunk_ctx *c = p;
    for (int32_t k = 0; k < c->ndyn; k++) {
        cpVect q = cpBodyGetPosition(c->dyn[k]), v = cpBodyGetVelocity(c->dyn[k]);
        x[k] = (float)q.x;
        y[k] = (float)q.y;
        vx[k] = (float)v.x;
        vy[k] = (float)v.y;
    }
}

static size_t chipmunk_bytes(void *p, size_t *peak)
{
    (void)p;
    *peak = 0;
    return 0;
}

static const char *chipmunk_version(void)
{
    static char text[32];
    cpSpaceFree(cpSpaceNew()); /* a debug build prints its banner here, not amid the table */
    snprintf(text, sizeof text, "Chipmunk %s", cpVersionString);
    return text;
}

const bench_engine bench_chipmunk_engine = {
    .name = "chipmunk", .create = chipmunk_create, .step = chipmunk_step, .force = chipmunk_force,
    .impulse = chipmunk_impulse, .read = chipmunk_read, .bytes = chipmunk_bytes,
    .destroy = chipmunk_destroy, .version = chipmunk_version,
};
