/* bench.h: what the benchmark harness shares with its engines (rigid, Box2D 2.4, Chipmunk 7,
 * Box2D v3 loaded from its own build, the floor loop) and its parts (scenes, quality, report).
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
    double nx, ny;     /* static only: a one-way shape's normal, (0, 0) two-way (rigid only) */
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
    /* Rigid's gameplay collision (tools/bench_gameplay.c): BENCH_PLAIN, or with sleeping
     * off BENCH_AWAKE, BENCH_ONE_WAY (bodies[].nx, ny set), BENCH_PRE_SOLVE (a hook that
     * keeps every pair), BENCH_VERLET or BENCH_RK4 (that integrator instead of the
     * default). */
    int32_t variant;
    /* Run settings, set by the harness before each create: the same for every engine. */
    int32_t sleep;       /* 1: sleeping on, with the engine's own thresholds; 0: off */
    int32_t workers;     /* threads the engine may use, >= 1 (only engines with threaded) */
    int32_t solver_set;  /* 1: use solver[], 0: the engine's default setting */
    int32_t solver[2];   /* rigid and Box2D 2.4: velocity, position iterations; Box2D v3:
                            substeps; Chipmunk: iterations (solver[1] unused) */
} bench_scene;

enum { BENCH_PLAIN = 0, BENCH_AWAKE = 1, BENCH_ONE_WAY = 2, BENCH_PRE_SOLVE = 3, BENCH_VERLET = 4,
       BENCH_RK4 = 5 };

/* What the contacts of the last step were: touching pairs, those of them with a one-way
 * shape, and the calls the pre-solve hook had in that step. */
typedef struct bench_contacts {
    double touching, one_way, pre_solve_calls;
} bench_contacts;

/* One engine.  create returns NULL when the scene needs what the engine lacks.  Every
 * pointer after destroy may be NULL (the engine cannot tell or do it). */
typedef struct bench_engine {
    const char *name;
    int32_t threaded;   /* 1: create honours s->workers > 1 */
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
    /* The contacts of the last step, or NULL when the engine cannot tell. */
    void (*contacts)(void *ctx, bench_contacts *out);
    /* Snapshots (tools/bench_snapshot.c): save writes the world into buf (cap bytes) and
     * returns the bytes it needs (writing nothing when that is more than cap, or when buf is
     * NULL), 0 on failure; restore loads an image into the world of ctx, 1 on success; hash
     * digests the simulation state. */
    size_t (*save)(void *ctx, void *buf, size_t cap);
    int (*restore)(void *ctx, const void *buf, size_t size);
    uint64_t (*hash)(void *ctx);
    /* Kept states, NULL when the engine has none: keep copies the world's state into a slot
     * of its own, back brings it back; 1 on success. */
    int (*keep)(void *ctx, int slot);
    int (*back)(void *ctx, int slot);
} bench_engine;

/* tools/bench_gameplay.c: the scenes that measure what one-way shapes and a pre-solve hook
 * cost (rigid only), and their report.  bench_gameplay_variant turns a built scene into
 * its variant: for BENCH_ONE_WAY every static box one-way (a box taller than wide is a wall
 * facing the line x = 0, any other a floor or platform facing up). */
void bench_gameplay_variant(bench_scene *s, int32_t variant);

/* One result for the report. */
typedef struct bench_gameplay_row {
    const char *scene, *base;   /* base: the scene built (a variant is compared with its
                                   BENCH_AWAKE row of the same base and n) */
    int32_t n, variant;
    double ms, ms_lo, ms_hi;    /* median ms per step: over the runs, and their range */
    bench_contacts per_step;    /* mean contacts per step over all steps */
} bench_gameplay_row;
void bench_gameplay_report(const bench_gameplay_row *rows, int32_t nrows);

extern const bench_engine bench_rigid_engine;
/* The rg_world of a world bench_rigid_engine.create made (as void *: this header names no
 * engine's types), for tools that set what the engine interface has no call for. */
void *bench_rigid_world(void *ctx);
extern const bench_engine bench_floor_engine;   /* tools/bench_floor.c */
#ifdef RG_BENCH_PEERS
extern const bench_engine bench_box2d_engine;
extern const bench_engine bench_chipmunk_engine;
#endif

/* tools/bench_v3_load.c: the Box2D v3 engines tools/bench_v3.mk builds into shared libraries
 * (one per SIMD build, each with its own copy of v3), loaded at run time from dir (NULL: the
 * directory bench-v3/ beside the running program; "none": not at all).  out[0] gets the SSE2
 * build, out[1] the AVX2 build, NULL where one is missing or the CPU cannot run it; why gets
 * a sentence for each one missing.  Returns how many were loaded. */
int bench_v3_load(const char *dir, const bench_engine *out[2], char *why, size_t why_size);
/* 1 when the CPU runs AVX2 and FMA (what v3's AVX2 build needs and rigid's dispatch picks). */
int bench_cpu_has_avx2(void);

/* ---------------------------------------------------------------- scenes (bench_scenes.c) */

typedef struct bench_scene_def {
    const char *name;
    const char *what;
    int32_t default_sizes[4];
    int32_t quick_size;
    int shaped;         /* needs collision */
    int settles;        /* a pile that should come to rest */
    int sleep_both;     /* by default run with sleeping off and on (else as sleep_default) */
    int sleep_default;  /* the sleeping setting it runs with when not both */
    const char *base;   /* a gameplay variant (rigid only, tools/bench_gameplay.c): the scene
                           it builds; NULL for the others */
    int32_t variant;    /* BENCH_PLAIN, BENCH_AWAKE, BENCH_ONE_WAY, BENCH_PRE_SOLVE, BENCH_VERLET,
                           BENCH_RK4 */
} bench_scene_def;

extern const bench_scene_def bench_scenes[];
extern const int bench_nscenes;
const bench_scene_def *bench_scene_find(const char *name);
/* Builds the scene (bodies malloc'ed: free(s->bodies)); run settings: sleeping as the
 * definition says, one worker, default solver.  0 when out of memory. */
int bench_scene_build(bench_scene *s, const bench_scene_def *d, int32_t n);

/* ---------------------------------------------------------------- quality (bench_quality.c) */

typedef struct bench_quality {
    double overlap;      /* deepest overlap between two moving bodies, m */
    double wall;         /* deepest overlap of a moving body with a static shape, m */
    double mean_overlap; /* mean depth over the overlapping pairs (moving-moving and
                            moving-static), m; 0 when none overlaps */
    double peak;         /* deepest overlap (bodies or statics) over the run, sampled every
                            few steps with the rest time; NaN when not sampled */
    double vmax;         /* largest speed at the end, m/s */
    double rest;         /* s until the fastest shaped body stays below BENCH_REST_SPEED; <0 never */
    int32_t lost;        /* bodies that left the container */
} bench_quality;

#define BENCH_REST_SPEED 0.1  /* m/s: a pile whose fastest body is slower than this is at rest */

/* Overlaps (shaped scenes), vmax and lost from the dynamic bodies' state in list order. */
void bench_quality_measure(const bench_scene *s, const float *x, const float *y, const float *vx,
                           const float *vy, bench_quality *q);
/* The deepest overlap now, between two moving bodies or a moving body and a static shape. */
double bench_deepest_overlap(const bench_scene *s, const float *x, const float *y);
/* Largest speed of the dynamic bodies (of those with a shape when shaped_only). */
double bench_max_speed(const bench_scene *s, const float *vx, const float *vy, int shaped_only);

#ifdef __cplusplus
}
#endif

#endif
