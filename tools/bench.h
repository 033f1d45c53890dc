/* bench.h: what the benchmark harness shares with its engines (rigid, Box2D 2.4, Chipmunk 7).
 *
 * A scene is engine-neutral data: world settings and a list of bodies.  Each engine builds
 * the same list in the same order, steps it, and hands back the state of its dynamic bodies
 * (in list order) so that the harness measures quality with one piece of code for all. */
#ifndef RG_BENCH_H
#define RG_BENCH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { BENCH_SHAPE_NONE = 0, BENCH_SHAPE_CIRCLE = 1, BENCH_SHAPE_BOX = 2 };
enum { BENCH_STATIC = 0, BENCH_DYNAMIC = 1 };

typedef struct bench_body {
    double x, y;       /* m */
    double vx, vy;     /* m/s, dynamic only */
    double mass;       /* kg, dynamic only */
    double a, b;       /* circle: radius, b unused; box: half width, half height (m) */
    int32_t shape;     /* BENCH_SHAPE_* */
    int32_t type;      /* BENCH_STATIC | BENCH_DYNAMIC */
    int32_t sensor;    /* 1: reports overlaps, never pushes */
    int32_t pad;
} bench_body;

/* A scene that pushes its bodies every step (the platformer's walkers) does it through
 * these calls, the same on every engine; k indexes the dynamic bodies in list order. */
typedef struct bench_pusher {
    void *ctx;
    void (*force)(void *ctx, int32_t k, double fx, double fy);     /* N, this step */
    void (*impulse)(void *ctx, int32_t k, double ix, double iy);   /* N*s, now */
} bench_pusher;

typedef struct bench_scene {
    char name[32];
    int32_t size;            /* the N the scene is named by */
    double gx, gy;           /* gravity, m/s^2 */
    double damping;          /* linear drag per unit mass, 1/s: F = -damping * m * v, on every
                                dynamic body (Box2D linearDamping, Chipmunk space damping) */
    double friction;         /* contact friction of a pair (each engine's mixing is undone) */
    double restitution;
    int32_t nbodies;
    int32_t ndynamic;
    bench_body *bodies;
    /* A container (floor top at y = 0, inner walls at +-half_width) to count escapees. */
    int32_t has_container;
    double half_width;
    /* Called before every step with the step index, or NULL. */
    void (*drive)(const struct bench_scene *s, int32_t step, const bench_pusher *p);
} bench_scene;

/* One engine.  create returns NULL when the scene needs what the engine lacks. */
typedef struct bench_engine {
    const char *name;
    void *(*create)(const bench_scene *s);
    void (*step)(void *ctx, double dt);
    void (*force)(void *ctx, int32_t k, double fx, double fy);
    void (*impulse)(void *ctx, int32_t k, double ix, double iy);
    /* State of the dynamic bodies, in list order (arrays of s->ndynamic). */
    void (*read)(void *ctx, float *x, float *y, float *vx, float *vy);
    /* Bytes the engine holds for this world now, or 0 when it cannot tell (the harness then
     * measures the heap); *peak gets the most it held at once, or 0 when unknown. */
    size_t (*bytes)(void *ctx, size_t *peak);
    void (*destroy)(void *ctx);
    /* Allocator calls so far (allocations, reallocations and frees), or NULL when the
     * engine cannot tell: the harness checks that a steady-state step makes none. */
    int64_t (*alloc_calls)(void *ctx);
    /* Name and version of the library actually linked. */
    const char *(*version)(void);
} bench_engine;

extern const bench_engine bench_rigid_engine;
#ifdef RG_BENCH_PEERS
extern const bench_engine bench_box2d_engine;
extern const bench_engine bench_chipmunk_engine;
#endif

#ifdef __cplusplus
}
#endif

#endif
