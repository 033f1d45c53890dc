/* bench.c: the benchmark harness: named scenes at several sizes on rigid and, when built
 * with them, Box2D 2.4 and Chipmunk 7 side by side.
 *
 *   bench [--quick] [--scene NAME[:N,N...]]... [--engine a,b] [--steps S] [--repeats R]
 *         [--csv FILE] [--dump FILE] [--list]
 *
 * Every engine runs the same body list (bench.h) for S steps of 1/60 s on one thread; each
 * step is timed alone.  A run gives the median, mean and 95th percentile of its step times;
 * a scene is run R times per engine, engines interleaved, and the figures printed are the
 * medians over the runs.  Quality is measured by one piece of code for every engine from
 * the state each hands back: the deepest overlap between two bodies and between a body and
 * a static shape, the largest speed at the end, when the pile came to rest, and how many
 * bodies left the container. */
#define _GNU_SOURCE 1 /* clock_gettime, mallinfo2 */
#include <malloc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"

#define BENCH_DT (1.0 / 60.0)
#define REST_SPEED 0.1   /* m/s: a pile whose fastest body is slower than this is at rest */
#define SAMPLE_EVERY 10  /* steps between (untimed) speed samples for the rest time */

/* ---------------------------------------------------------------- deterministic jitter */

/* splitmix64 of (index, stream): a number in [-1, 1) that depends on nothing else. */
static double jitter(uint64_t i, uint64_t stream)
{
    uint64_t z = i * 0x9E3779B97F4A7C15ull + stream * 0xD1B54A32D192ED03ull + 0x632BE59BD9B4E019ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/* ---------------------------------------------------------------- scenes */

static bench_body *add_body(bench_scene *s, int type, double x, double y)
{
    bench_body *b = &s->bodies[s->nbodies++];
    memset(b, 0, sizeof *b);
    b->type = type;
    b->x = x;
    b->y = y;
    if (type == BENCH_DYNAMIC) s->ndynamic++;
    return b;
}

static void add_static_box(bench_scene *s, double x0, double y0, double x1, double y1)
{
    bench_body *b = add_body(s, BENCH_STATIC, (x0 + x1) / 2, (y0 + y1) / 2);
    b->shape = BENCH_SHAPE_BOX;
    b->a = (x1 - x0) / 2;
    b->b = (y1 - y0) / 2;
}

/* The container and spawn grid: floor top at y = 0, two 1 m walls, inner width
 * ceil(sqrt(n)) + 0.5; bodies on a 1.1 m grid, the lowest row's centres 1 m above the
 * floor, each jittered by +-0.04 m in x and y.  shape: circle r 0.5 density 1, or unit
 * box of mass 1. */
static void pile(bench_scene *s, int32_t n, int shape, double x_offset)
{
    double inner = ceil(sqrt((double)n)) + 0.5, half = inner / 2;
    int32_t cols = (int32_t)floor((inner - 1.0 - 0.08) / 1.1) + 1;
    int32_t rows = (n + cols - 1) / cols;
    double top = 1.0 + 1.1 * rows + 2.0;
    add_static_box(s, x_offset - half - 1, -1, x_offset + half + 1, 0);         /* floor */
    add_static_box(s, x_offset - half - 1, 0, x_offset - half, top);            /* walls */
    add_static_box(s, x_offset + half, 0, x_offset + half + 1, top);
    double x0 = x_offset - 1.1 * (cols - 1) / 2;
    for (int32_t i = 0; i < n; i++) {
        double x = x0 + 1.1 * (i % cols) + 0.04 * jitter((uint64_t)i, 1);
        double y = 1.0 + 1.1 * (i / cols) + 0.04 * jitter((uint64_t)i, 2);
        bench_body *b = add_body(s, BENCH_DYNAMIC, x, y);
        b->shape = shape;
        if (shape == BENCH_SHAPE_CIRCLE) {
            b->a = 0.5;
            b->mass = M_PI * 0.25;
        } else {
            b->a = b->b = 0.5;
            b->mass = 1;
        }
    }
    s->has_container = 1;
    s->half_width = half;
}

/* n bodies without shapes on a 2 m grid, mass 1, starting at x_offset. */
static void particles(bench_scene *s, int32_t n, double x_offset)
{
    int32_t cols = (int32_t)ceil(sqrt((double)n));
    for (int32_t i = 0; i < n; i++) {
        bench_body *b = add_body(s, BENCH_DYNAMIC, x_offset + 2.0 * (i % cols), 2.0 * (i / cols));
        b->mass = 1;
    }
}

/* Platformer walkers: a sideways push of 8 N (friction holds back 6 N on the ground) that
 * turns every 2 s and a jump (6 N*s) every 1.5 s, both staggered per walker. */
#define PLATFORMER_WALKERS 256
static void platformer_drive(const bench_scene *s, int32_t step, const bench_pusher *p)
{
    (void)s;
    for (int32_t k = 0; k < PLATFORMER_WALKERS; k++) {
        double dir = (((step + 7 * k) / 120) & 1) ? -1.0 : 1.0;
        p->force(p->ctx, k, 8.0 * dir, 0.0);
        if ((step + 11 * k) % 90 == 0) p->impulse(p->ctx, k, 0.0, 6.0);
    }
}

/* n static unit tiles: half of them a ground row with its top at y = 0, the rest platforms
 * of 6 tiles, 9 tiles apart, in layers 3 m apart; 256 walkers (0.8 m boxes, 1 kg). */
static void platformer(bench_scene *s, int32_t n)
{
    int32_t plat = (n - n / 2) / 6, ground = n - 6 * plat;
    for (int32_t i = 0; i < PLATFORMER_WALKERS; i++) {
        bench_body *b = add_body(s, BENCH_DYNAMIC, (i + 0.5) * ground / PLATFORMER_WALKERS, 0.9);
        b->shape = BENCH_SHAPE_BOX;
        b->a = b->b = 0.4;
        b->mass = 1;
    }
    for (int32_t i = 0; i < ground; i++) add_static_box(s, i, -1, i + 1, 0);
    int32_t span = ground - 6 > 1 ? ground - 6 : 1;
    for (int32_t j = 0; j < plat; j++) {
        int32_t col = (j * 9) % span, layer = (j * 9) / span;
        double y = 3.0 + 3.0 * layer;
        for (int32_t t = 0; t < 6; t++) add_static_box(s, col + t, y, col + t + 1, y + 1);
    }
    s->drive = platformer_drive;
}

/* n static sensor boxes (coins, 0.5 m) on a 2 m grid and n/10 circles (r 0.25, 1 kg)
 * drifting through them at 4 m/s in deterministic directions, without gravity. */
static void sensors(bench_scene *s, int32_t n)
{
    int32_t m = n / 10 > 0 ? n / 10 : 1;
    int32_t cols = (int32_t)ceil(sqrt((double)n));
    int32_t mcols = (int32_t)ceil(sqrt((double)m));
    double side = 2.0 * cols, spacing = side / mcols;
    for (int32_t i = 0; i < m; i++) {
        bench_body *b = add_body(s, BENCH_DYNAMIC, 1.0 + spacing * (i % mcols), 1.0 + spacing * (i / mcols));
        double ang = M_PI * jitter((uint64_t)i, 3);
        b->vx = 4.0 * cos(ang);
        b->vy = 4.0 * sin(ang);
        b->shape = BENCH_SHAPE_CIRCLE;
        b->a = 0.25;
        b->mass = 1;
    }
    for (int32_t i = 0; i < n; i++) {
        bench_body *b = add_body(s, BENCH_STATIC, 2.0 * (i % cols), 2.0 * (i / cols));
        b->shape = BENCH_SHAPE_BOX;
        b->a = b->b = 0.25;
        b->sensor = 1;
    }
    s->gy = 0;
}

typedef struct scene_def {
    const char *name;
    const char *what;
    int32_t default_sizes[4];
    int32_t quick_size;
    int shaped;   /* needs collision */
    int settles;  /* a pile that should come to rest */
    const char *base;   /* a gameplay variant (rigid only, tools/bench_gameplay.c): the scene
                           it builds; NULL for the others */
    int32_t variant;    /* BENCH_PLAIN, BENCH_AWAKE, BENCH_ONE_WAY, BENCH_PRE_SOLVE */
} scene_def;

static const scene_def SCENES[] = {
    { "rain", "circles r 0.5 falling into a container", { 1000, 4000, 10000, 0 },
      1000, 1, 1, NULL, BENCH_PLAIN },
    { "boxes", "unit boxes falling into a container", { 4000, 10000, 0, 0 },
      1000, 1, 1, NULL, BENCH_PLAIN },
    { "free0", "bodies without shapes, gravity + linear drag 0.1*m", { 100000, 0, 0, 0 },
      10000, 0, 0, NULL, BENCH_PLAIN },
    { "free-nodrag", "free0 without drag (a force nobody set)", { 100000, 0, 0, 0 },
      10000, 0, 0, NULL, BENCH_PLAIN },
    { "sparse", "N bodies, 1% of them circles raining in a container", { 100000, 0, 0, 0 },
      10000, 1, 0, NULL, BENCH_PLAIN },
    { "platformer", "N static tiles, 256 walkers pushing and jumping", { 10000, 100000, 0, 0 },
      10000, 1, 0, NULL, BENCH_PLAIN },
    { "sensors", "N static sensor boxes, N/10 circles drifting through", { 10000, 0, 0, 0 },
      2000, 1, 0, NULL, BENCH_PLAIN },
    /* rigid's gameplay collision, sleeping off (tools/bench_gameplay.c) */
    { "rain-awake", "rain, sleeping off (what the two below compare with)", { 4000, 0, 0, 0 },
      1000, 1, 1, "rain", BENCH_AWAKE },
    { "rain-oneway", "rain-awake, floor and walls one-way", { 4000, 0, 0, 0 },
      1000, 1, 1, "rain", BENCH_ONE_WAY },
    { "rain-presolve", "rain-awake, a pre-solve hook keeping every pair", { 4000, 0, 0, 0 },
      1000, 1, 1, "rain", BENCH_PRE_SOLVE },
    { "boxes-awake", "boxes, sleeping off", { 4000, 0, 0, 0 }, 1000, 1, 1, "boxes", BENCH_AWAKE },
    { "boxes-oneway", "boxes-awake, floor and walls one-way", { 4000, 0, 0, 0 },
      1000, 1, 1, "boxes", BENCH_ONE_WAY },
    { "boxes-presolve", "boxes-awake, a pre-solve hook keeping every pair", { 4000, 0, 0, 0 },
      1000, 1, 1, "boxes", BENCH_PRE_SOLVE },
    { "platformer-awake", "platformer, sleeping off", { 10000, 0, 0, 0 },
      10000, 1, 0, "platformer", BENCH_AWAKE },
    { "platformer-oneway", "platformer-awake, every tile one-way, facing up", { 10000, 0, 0, 0 },
      10000, 1, 0, "platformer", BENCH_ONE_WAY },
    { "platformer-presolve", "platformer-awake, a pre-solve hook keeping every pair",
      { 10000, 0, 0, 0 }, 10000, 1, 0, "platformer", BENCH_PRE_SOLVE },
};
#define NSCENES ((int)(sizeof SCENES / sizeof SCENES[0]))

static const scene_def *scene_find(const char *name)
{
    for (int i = 0; i < NSCENES; i++)
        if (strcmp(SCENES[i].name, name) == 0) return &SCENES[i];
    return NULL;
}

static int scene_build(bench_scene *s, const scene_def *d, int32_t n)
{
    const char *kind = d->base != NULL ? d->base : d->name;
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", d->name);
    s->size = n;
    s->gy = -10;
    s->friction = 0.6;
    int32_t cap = n + 3;
    if (strcmp(kind, "platformer") == 0) cap = n + PLATFORMER_WALKERS;
    if (strcmp(kind, "sensors") == 0) cap = n + n / 10 + 1;
    s->bodies = malloc((size_t)cap * sizeof *s->bodies);
    if (s->bodies == NULL) return 0;
    if (strcmp(kind, "rain") == 0) {
        pile(s, n, BENCH_SHAPE_CIRCLE, 0);
    } else if (strcmp(kind, "boxes") == 0) {
        pile(s, n, BENCH_SHAPE_BOX, 0);
    } else if (strcmp(kind, "free0") == 0) {
        particles(s, n, 0);
        s->damping = 0.1;
    } else if (strcmp(kind, "free-nodrag") == 0) {
        particles(s, n, 0);
    } else if (strcmp(kind, "sparse") == 0) {
        int32_t shaped = n / 100 > 0 ? n / 100 : 1;
        pile(s, shaped, BENCH_SHAPE_CIRCLE, 0);
        particles(s, n - shaped, 100.0 + ceil(sqrt((double)shaped)));
    } else if (strcmp(kind, "platformer") == 0) {
        platformer(s, n);
    } else if (strcmp(kind, "sensors") == 0) {
        sensors(s, n);
    }
    bench_gameplay_variant(s, d->variant);
    return 1;
}

/* ---------------------------------------------------------------- the floor reference */

/* A plain C loop over four float arrays (x, y, vx, vy) doing the least a free-particle step
 * can do (semi-implicit Euler, gravity, linear drag), vectorised (SSE2 in the default
 * build): the floor rigid's free scenes are compared with.  32 bytes per body-step, where
 * rigid's pass also reads mass, gravity scale, applied force and the drag coefficients and
 * writes the acceleration. */
typedef struct floor_ctx {
    float *x, *y, *vx, *vy;
    int32_t n;
    float gx, gy, c;
} floor_ctx;

static void floor_destroy(void *p)
{
    floor_ctx *f = p;
    if (f == NULL) return;
    free(f->x);
    free(f);
}

static void *floor_create(const bench_scene *s)
{
    for (int32_t i = 0; i < s->nbodies; i++)
        if (s->bodies[i].shape != BENCH_SHAPE_NONE || s->bodies[i].type != BENCH_DYNAMIC) return NULL;
    if (s->drive != NULL) return NULL;
    floor_ctx *f = calloc(1, sizeof *f);
    if (f == NULL) return NULL;
    size_t n = (size_t)s->nbodies;
    f->x = malloc(4 * n * sizeof *f->x + 1);
    if (f->x == NULL) {
        free(f);
        return NULL;
    }
    f->y = f->x + n;
    f->vx = f->y + n;
    f->vy = f->vx + n;
    for (size_t i = 0; i < n; i++) {
        f->x[i] = (float)s->bodies[i].x;
        f->y[i] = (float)s->bodies[i].y;
        f->vx[i] = (float)s->bodies[i].vx;
        f->vy[i] = (float)s->bodies[i].vy;
    }
    f->n = s->nbodies;
    f->gx = (float)s->gx;
    f->gy = (float)s->gy;
    f->c = (float)s->damping;
    return f;
}

/* Blocks of a constant length with restrict pointers: vectorised at -O2, and built for AVX2
 * as well where rigid's Euler pass is (src/integrator.c), so the two compare like for like. */
#define FLOOR_BLOCK 64
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__) && \
    !defined(RG_NO_DISPATCH)
#define FLOOR_DISPATCH __attribute__((target_clones("avx2", "default")))
#define FLOOR_INLINE __attribute__((always_inline)) inline
#else
#define FLOOR_DISPATCH
#define FLOOR_INLINE inline
#endif

static FLOOR_INLINE void floor_block(float *restrict x, float *restrict y, float *restrict vx, float *restrict vy,
                        float h, float gx, float gy, float c)
{
    for (int i = 0; i < FLOOR_BLOCK; i++) {
        float nvx = vx[i] + (gx - c * vx[i]) * h, nvy = vy[i] + (gy - c * vy[i]) * h;
        vx[i] = nvx;
        vy[i] = nvy;
        x[i] += nvx * h;
        y[i] += nvy * h;
    }
}

FLOOR_DISPATCH static void floor_step(void *p, double dt)
{
    floor_ctx *f = p;
    float h = (float)dt, gx = f->gx, gy = f->gy, c = f->c;
    int32_t i = 0;
    for (; i + FLOOR_BLOCK <= f->n; i += FLOOR_BLOCK)
        floor_block(f->x + i, f->y + i, f->vx + i, f->vy + i, h, gx, gy, c);
    for (; i < f->n; i++) {
        float nvx = f->vx[i] + (gx - c * f->vx[i]) * h, nvy = f->vy[i] + (gy - c * f->vy[i]) * h;
        f->vx[i] = nvx;
        f->vy[i] = nvy;
        f->x[i] += nvx * h;
        f->y[i] += nvy * h;
    }
}

static void floor_push(void *p, int32_t k, double fx, double fy)
{
    (void)p;
    (void)k;
    (void)fx;
    (void)fy;
}

static void floor_read(void *p, float *x, float *y, float *vx, float *vy)
{
    floor_ctx *f = p;
    size_t n = (size_t)f->n * sizeof(float);
    memcpy(x, f->x, n);
    memcpy(y, f->y, n);
    memcpy(vx, f->vx, n);
    memcpy(vy, f->vy, n);
}

static size_t floor_bytes(void *p, size_t *peak)
{
    const floor_ctx *f = p;
    *peak = 4 * (size_t)f->n * sizeof(float);
    return *peak;
}

static const char *floor_version(void) { return "floor: a vectorised C loop over x, y, vx, vy"; }

static const bench_engine floor_engine = {
    "floor", floor_create, floor_step, floor_push, floor_push, floor_read, floor_bytes,
    floor_destroy, NULL, floor_version, NULL,
};

/* ---------------------------------------------------------------- engines */

static const bench_engine *const ENGINES[] = {
    &bench_rigid_engine,
#ifdef RG_BENCH_PEERS
    &bench_box2d_engine,
    &bench_chipmunk_engine,
#endif
    &floor_engine,
};
#define NENGINES ((int)(sizeof ENGINES / sizeof ENGINES[0]))

/* Box2D v3.2 on the machine: a quoted figure (v3 is not packaged), ms per step. */
typedef struct reference {
    const char *scene;
    int32_t n;
    double box2d24, chipmunk7, box2d_v3;
} reference;

static const reference REFERENCES[] = {
    { "rain", 4000, 4.3, 2.6, 1.20 },    { "rain", 10000, 22.0, 17.4, 8.2 },
    { "boxes", 4000, 6.6, 5.0, 1.23 },   { "boxes", 10000, 37.9, 20.6, 6.0 },
    { "free0", 100000, 24.1, 4.3, 3.6 },
};

/* ---------------------------------------------------------------- timing and statistics */

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median and nearest-rank percentile of v[0..n) (sorts v). */
static double quantile(double *v, int32_t n, double q)
{
    if (n <= 0) return (double)NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    if (q == 0.5) return (n & 1) ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
    int32_t k = (int32_t)ceil(q * n) - 1;
    if (k < 0) k = 0;
    if (k >= n) k = n - 1;
    return v[k];
}

static size_t heap_in_use(void)
{
    struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
}

/* ---------------------------------------------------------------- quality */

typedef struct quality {
    double overlap;      /* deepest overlap between two moving bodies, m */
    double wall;         /* deepest overlap of a moving body with a static shape, m */
    double vmax;         /* largest speed at the end, m/s */
    double rest;         /* s until the fastest shaped body stays below REST_SPEED; <0 never */
    int32_t lost;        /* bodies that left the container */
} quality;

/* Overlap depth of two shapes (negative when apart). */
static double shape_overlap(int sa, double xa, double ya, double aa, double ba,
                            int sb, double xb, double yb, double ab, double bb)
{
    if (sa == BENCH_SHAPE_BOX && sb == BENCH_SHAPE_CIRCLE)
        return shape_overlap(sb, xb, yb, ab, bb, sa, xa, ya, aa, ba);
    double dx = xb - xa, dy = yb - ya;
    if (sa == BENCH_SHAPE_CIRCLE && sb == BENCH_SHAPE_CIRCLE) return aa + ab - sqrt(dx * dx + dy * dy);
    if (sa == BENCH_SHAPE_BOX) { /* box-box */
        double ox = aa + ab - fabs(dx), oy = ba + bb - fabs(dy);
        return ox < oy ? ox : oy;
    }
    /* circle a against box b */
    double px = fabs(dx), py = fabs(dy); /* circle centre relative to box, folded */
    if (px <= ab && py <= bb) {          /* centre inside: distance to leave + radius */
        double ex = ab - px, ey = bb - py;
        return aa + (ex < ey ? ex : ey);
    }
    double qx = px > ab ? px - ab : 0, qy = py > bb ? py - bb : 0;
    return aa - sqrt(qx * qx + qy * qy);
}

typedef struct qitem {
    double x, y, a, b;
    int32_t shape, dynamic;
} qitem;

static uint32_t cell_hash(int64_t cx, int64_t cy)
{
    uint64_t h = (uint64_t)cx * 0x9E3779B97F4A7C15ull ^ (uint64_t)cy * 0xC2B2AE3D27D4EB4Full;
    return (uint32_t)(h >> 32);
}

/* Deepest overlaps, over a hash grid of the small shapes; shapes larger than a cell
 * (container walls) are checked against every moving body. */
static void measure_overlaps(const bench_scene *s, const float *x, const float *y, quality *q)
{
    int32_t n = s->nbodies, ni = 0, nbig = 0, nstatic = 0;
    qitem *it = malloc((size_t)n * sizeof *it);
    int32_t *big = malloc((size_t)n * sizeof *big);
    double maxhalf = 0;
    q->overlap = -(double)INFINITY;
    q->wall = -(double)INFINITY;
    if (it == NULL || big == NULL) goto done;
    int32_t k = 0;
    for (int32_t i = 0; i < n; i++) {
        const bench_body *bb = &s->bodies[i];
        int dyn = bb->type == BENCH_DYNAMIC;
        int32_t kk = dyn ? k++ : -1;
        if (bb->shape == BENCH_SHAPE_NONE || bb->sensor) continue;
        qitem *e = &it[ni];
        e->x = dyn ? (double)x[kk] : bb->x;
        e->y = dyn ? (double)y[kk] : bb->y;
        e->a = bb->a;
        e->b = bb->shape == BENCH_SHAPE_CIRCLE ? bb->a : bb->b;
        e->shape = bb->shape;
        e->dynamic = dyn;
        nstatic += !dyn;
        if (e->a > 1.0 || e->b > 1.0) {
            big[nbig++] = ni;
        } else {
            if (e->a > maxhalf) maxhalf = e->a;
            if (e->b > maxhalf) maxhalf = e->b;
        }
        ni++;
    }
    for (int32_t i = 0; i < ni; i++) { /* big statics against every moving body */
        if (!it[i].dynamic) continue;
        for (int32_t j = 0; j < nbig; j++) {
            const qitem *a = &it[i], *b = &it[big[j]];
            double o = shape_overlap(a->shape, a->x, a->y, a->a, a->b, b->shape, b->x, b->y, b->a, b->b);
            if (o > q->wall) q->wall = o;
        }
    }
    double cell = 2 * maxhalf > 0 ? 2 * maxhalf : 1;
    uint32_t size = 1;
    while (size < 2u * (uint32_t)ni) size <<= 1;
    int32_t *head = malloc((size_t)size * sizeof *head), *next = malloc((size_t)ni * sizeof *next);
    if (head == NULL || next == NULL) {
        free(head);
        free(next);
        goto done;
    }
    for (uint32_t i = 0; i < size; i++) head[i] = -1;
    for (int32_t i = 0; i < ni; i++) {
        if (it[i].a > 1.0 || it[i].b > 1.0) continue;
        uint32_t h = cell_hash((int64_t)floor(it[i].x / cell), (int64_t)floor(it[i].y / cell)) & (size - 1);
        next[i] = head[h];
        head[h] = i;
    }
    for (int32_t i = 0; i < ni; i++) {
        const qitem *a = &it[i];
        if (!a->dynamic || a->a > 1.0 || a->b > 1.0) continue;
        int64_t cx = (int64_t)floor(a->x / cell), cy = (int64_t)floor(a->y / cell);
        for (int64_t dy = -1; dy <= 1; dy++)
            for (int64_t dx = -1; dx <= 1; dx++)
                for (int32_t j = head[cell_hash(cx + dx, cy + dy) & (size - 1)]; j >= 0; j = next[j]) {
                    const qitem *b = &it[j];
                    if (j == i || (b->dynamic && j < i)) continue;
                    double o = shape_overlap(a->shape, a->x, a->y, a->a, a->b, b->shape, b->x, b->y, b->a, b->b);
                    if (b->dynamic) {
                        if (o > q->overlap) q->overlap = o;
                    } else if (o > q->wall) {
                        q->wall = o;
                    }
                }
    }
    free(head);
    free(next);
done:
    /* Apart is no overlap (and no static shape at all stays -inf: "none"). */
    if (q->overlap < 0) q->overlap = 0;
    if (q->wall < 0 && nstatic > 0) q->wall = 0;
    free(it);
    free(big);
}

static double max_speed(const bench_scene *s, const float *vx, const float *vy, int shaped_only)
{
    double m = 0;
    int32_t k = 0;
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body *bb = &s->bodies[i];
        if (bb->type != BENCH_DYNAMIC) continue;
        if (!shaped_only || bb->shape != BENCH_SHAPE_NONE) {
            double vxk = (double)vx[k], vyk = (double)vy[k];
            double v = sqrt(vxk * vxk + vyk * vyk);
            if (v > m || v != v) m = v;
        }
        k++;
    }
    return m;
}

static int32_t count_lost(const bench_scene *s, const float *x, const float *y)
{
    if (!s->has_container) return 0;
    int32_t lost = 0, k = 0;
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body *bb = &s->bodies[i];
        if (bb->type != BENCH_DYNAMIC) continue;
        if (bb->shape != BENCH_SHAPE_NONE &&
            (!(y[k] > -0.5f) || !(fabs((double)x[k]) < s->half_width + 0.5)))
            lost++;
        k++;
    }
    return lost;
}

/* ---------------------------------------------------------------- one run */

typedef struct run_result {
    int ok;
    double median, mean, p95;  /* ms per step */
    double settling;           /* mean ms per step until the rest time (all steps if none) */
    size_t bytes, peak;
    int64_t steady_allocs;     /* allocator calls in the second half of the steps; -1 unknown */
    quality q;
    bench_contacts contacts;   /* mean per step over all steps */
} run_result;

typedef struct state_buf {
    float *x, *y, *vx, *vy;
} state_buf;

static void push_force(void *ctx, int32_t k, double fx, double fy);
static void push_impulse(void *ctx, int32_t k, double ix, double iy);

typedef struct push_ctx {
    const bench_engine *e;
    void *ctx;
} push_ctx;

static void push_force(void *ctx, int32_t k, double fx, double fy)
{
    push_ctx *p = ctx;
    p->e->force(p->ctx, k, fx, fy);
}

static void push_impulse(void *ctx, int32_t k, double ix, double iy)
{
    push_ctx *p = ctx;
    p->e->impulse(p->ctx, k, ix, iy);
}

/* --dump: the final state of every dynamic body of every run, for a closer look. */
static FILE *dump_file;

static run_result run_once(const bench_engine *e, const bench_scene *s, const scene_def *d,
                           int32_t steps, double *times, state_buf *st)
{
    run_result r;
    memset(&r, 0, sizeof r);
    size_t heap0 = heap_in_use();
    void *ctx = e->create(s);
    if (ctx == NULL) return r;
    push_ctx pc = { e, ctx };
    bench_pusher pusher = { &pc, push_force, push_impulse };
    double last_moving = 0; /* time of the last sample with a shaped body above REST_SPEED */
    int sample = d->settles;
    int64_t calls_half = 0;
    r.steady_allocs = -1;
    for (int32_t i = 0; i < steps; i++) {
        if (i == steps / 2 && e->alloc_calls != NULL) calls_half = e->alloc_calls(ctx);
        double t0 = now_ms();
        if (s->drive != NULL) s->drive(s, i, &pusher);
        e->step(ctx, BENCH_DT);
        times[i] = now_ms() - t0;
        if (e->contacts != NULL) {
            bench_contacts c;
            e->contacts(ctx, &c);
            r.contacts.touching += c.touching / steps;
            r.contacts.one_way += c.one_way / steps;
            r.contacts.pre_solve_calls += c.pre_solve_calls / steps;
        }
        if (sample && (i + 1) % SAMPLE_EVERY == 0) {
            e->read(ctx, st->x, st->y, st->vx, st->vy);
            if (max_speed(s, st->vx, st->vy, 1) >= REST_SPEED) last_moving = (i + 1) * BENCH_DT;
        }
    }
    e->read(ctx, st->x, st->y, st->vx, st->vy);
    if (dump_file != NULL)
        for (int32_t k = 0; k < s->ndynamic; k++)
            fprintf(dump_file, "%s,%d,%s,%d,%.6g,%.6g,%.6g,%.6g\n", s->name, (int)s->size, e->name,
                    (int)k, (double)st->x[k], (double)st->y[k], (double)st->vx[k], (double)st->vy[k]);
    if (e->alloc_calls != NULL) r.steady_allocs = e->alloc_calls(ctx) - calls_half;
    size_t peak = 0, own = e->bytes(ctx, &peak);
    r.peak = peak;
    size_t heap1 = heap_in_use();
    r.bytes = own > 0 ? own : (heap1 > heap0 ? heap1 - heap0 : 0);
    r.q.vmax = max_speed(s, st->vx, st->vy, 0);
    r.q.overlap = r.q.wall = (double)NAN;
    if (d->shaped) measure_overlaps(s, st->x, st->y, &r.q);
    r.q.lost = count_lost(s, st->x, st->y);
    r.q.rest = (double)NAN;
    if (d->settles) r.q.rest = last_moving >= steps * BENCH_DT - 1e-9 ? -1 : last_moving;
    e->destroy(ctx);
    double sum = 0;
    for (int32_t i = 0; i < steps; i++) sum += times[i];
    r.mean = sum / steps;
    int32_t until = steps;
    if (d->settles && r.q.rest > 0) until = (int32_t)(r.q.rest / BENCH_DT + 0.5);
    if (until < 1) until = 1;
    if (until > steps) until = steps;
    double head = 0;
    for (int32_t i = 0; i < until; i++) head += times[i];
    r.settling = head / until;
    r.median = quantile(times, steps, 0.5);
    r.p95 = quantile(times, steps, 0.95);
    r.ok = 1;
    return r;
}

/* ---------------------------------------------------------------- results and output */

typedef struct result {
    char scene[32];
    int32_t n;
    const bench_engine *engine;
    int32_t nbodies, ndynamic;
    int32_t runs, steps;
    int ok;
    double median, mean, p95, min_median, max_median;
    double settling;    /* mean ms per step until the pile rests (all steps if it never does) */
    double ns_body;
    double bytes_body, peak_body; /* peak_body 0: unknown */
    int64_t steady_allocs;        /* most over the runs; -1 unknown */
    quality q;          /* of the last run (every run of a deterministic engine agrees) */
    const scene_def *def;
    bench_contacts contacts;      /* medians over the runs of the means per step */
} result;

static void combine(result *res, run_result *runs, int32_t nruns)
{
    double med[64], mean[64], p95[64], settle[64], touching[64], one_way[64], calls[64];
    int32_t k = 0;
    for (int32_t i = 0; i < nruns && k < 64; i++) {
        if (!runs[i].ok) continue;
        med[k] = runs[i].median;
        mean[k] = runs[i].mean;
        p95[k] = runs[i].p95;
        settle[k] = runs[i].settling;
        touching[k] = runs[i].contacts.touching;
        one_way[k] = runs[i].contacts.one_way;
        calls[k] = runs[i].contacts.pre_solve_calls;
        res->q = runs[i].q;
        res->bytes_body = (double)runs[i].bytes / (res->nbodies > 0 ? res->nbodies : 1);
        res->peak_body = (double)runs[i].peak / (res->nbodies > 0 ? res->nbodies : 1);
        k++;
    }
    res->steady_allocs = -1;
    for (int32_t i = 0; i < nruns; i++)
        if (runs[i].ok && runs[i].steady_allocs > res->steady_allocs) res->steady_allocs = runs[i].steady_allocs;
    res->ok = k > 0;
    res->runs = k;
    if (k == 0) return;
    res->median = quantile(med, k, 0.5);
    res->min_median = med[0];
    res->max_median = med[k - 1];
    res->mean = quantile(mean, k, 0.5);
    res->p95 = quantile(p95, k, 0.5);
    res->settling = quantile(settle, k, 0.5);
    res->contacts.touching = quantile(touching, k, 0.5);
    res->contacts.one_way = quantile(one_way, k, 0.5);
    res->contacts.pre_solve_calls = quantile(calls, k, 0.5);
    res->ns_body = res->median * 1e6 / (res->ndynamic > 0 ? res->ndynamic : 1);
}

static void fmt_q(char *buf, size_t size, double v, const char *f)
{
    if (v != v) snprintf(buf, size, "-");
    else if (isinf(v)) snprintf(buf, size, "none");
    else snprintf(buf, size, f, v);
}

static void print_header(void)
{
    printf("%-19s %7s %-9s %8s %8s %8s %7s %8s %8s %8s %8s %7s %6s %5s %12s\n", "scene", "N",
           "engine", "median", "mean", "p95", "spread", "ns/body", "B/body", "overlap", "wall",
           "vmax", "rest", "lost", "rigid/engine");
    printf("%-19s %7s %-9s %8s %8s %8s %7s %8s %8s %8s %8s %7s %6s %5s %12s\n", "", "", "",
           "ms/step", "ms/step", "ms/step", "%", "-step", "", "m", "m", "m/s", "s", "", "");
}

static void print_result(const result *r, const result *rigid)
{
    if (!r->ok) {
        printf("%-19s %7d %-9s %s\n", r->scene, (int)r->n, r->engine->name,
               r->engine == &bench_rigid_engine ? "n/a: scene needs collision this build lacks"
                                                : "n/a");
        return;
    }
    char ov[16], wl[16], rest[16], ratio[24];
    fmt_q(ov, sizeof ov, r->q.overlap, "%.4f");
    fmt_q(wl, sizeof wl, r->q.wall, "%.4f");
    if (r->q.rest != r->q.rest) snprintf(rest, sizeof rest, "-");
    else if (r->q.rest < 0) snprintf(rest, sizeof rest, "never");
    else snprintf(rest, sizeof rest, "%.2f", r->q.rest);
    if (rigid != NULL && rigid->ok && r != rigid)
        snprintf(ratio, sizeof ratio, "%.3f", rigid->median / r->median);
    else
        snprintf(ratio, sizeof ratio, "-");
    double spread = r->median > 0 ? 100.0 * (r->max_median - r->min_median) / r->median : 0;
    printf("%-19s %7d %-9s %8.3f %8.3f %8.3f %7.1f %8.2f %8.1f %8s %8s %7.3f %6s %5d %12s\n",
           r->scene, (int)r->n, r->engine->name, r->median, r->mean, r->p95, spread, r->ns_body,
           r->bytes_body, ov, wl, r->q.vmax, rest, (int)r->q.lost, ratio);
}

static void csv_header(FILE *f)
{
    fprintf(f, "scene,n,engine,bodies,dynamic,runs,steps,median_ms,mean_ms,p95_ms,min_median_ms,"
               "max_median_ms,ns_per_body_step,bytes_per_body,peak_bytes_per_body,max_overlap_m,max_wall_overlap_m,"
               "max_speed_end,rest_s,lost,steady_state_alloc_calls,settling_mean_ms\n");
}

static void csv_row(FILE *f, const result *r)
{
    if (!r->ok) return;
    fprintf(f, "%s,%d,%s,%d,%d,%d,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%.1f,%.1f,%.6g,%.6g,%.6g,%.4g,%d,%lld,%.6f\n",
            r->scene, (int)r->n, r->engine->name, (int)r->nbodies, (int)r->ndynamic, (int)r->runs,
            (int)r->steps, r->median, r->mean, r->p95, r->min_median, r->max_median, r->ns_body,
            r->bytes_body, r->peak_body, r->q.overlap, r->q.wall, r->q.vmax, r->q.rest, (int)r->q.lost,
            (long long)r->steady_allocs, r->settling);
}

static void machine(FILE *f)
{
    char model[128] = "unknown", family[16] = "?", modelno[16] = "?", line[256];
    FILE *c = fopen("/proc/cpuinfo", "r");
    if (c != NULL) {
        while (fgets(line, sizeof line, c) != NULL) {
            char *v = strchr(line, ':');
            if (v == NULL) continue;
            v++;
            while (*v == ' ' || *v == '\t') v++;
            v[strcspn(v, "\n")] = 0;
            if (strncmp(line, "model name", 10) == 0 && strcmp(model, "unknown") == 0)
                snprintf(model, sizeof model, "%s", v);
            else if (strncmp(line, "cpu family", 10) == 0 && family[0] == '?')
                snprintf(family, sizeof family, "%s", v);
            else if (strncmp(line, "model\t", 6) == 0 && modelno[0] == '?')
                snprintf(modelno, sizeof modelno, "%s", v);
        }
        fclose(c);
    }
    char load[64] = "?";
    FILE *l = fopen("/proc/loadavg", "r");
    if (l != NULL) {
        if (fgets(load, sizeof load, l) == NULL) snprintf(load, sizeof load, "?");
        load[strcspn(load, "\n")] = 0;
        fclose(l);
    }
    fprintf(f, "machine: %ld cpus, %s (family %s model %s); load average %s\n",
            sysconf(_SC_NPROCESSORS_ONLN), model, family, modelno, load);
}

/* ---------------------------------------------------------------- derived figures */

static const result *find(const result *rs, int32_t nr, const char *scene, int32_t n, const char *engine)
{
    for (int32_t i = 0; i < nr; i++)
        if (rs[i].ok && strcmp(rs[i].scene, scene) == 0 && (n == 0 || rs[i].n == n) &&
            strcmp(rs[i].engine->name, engine) == 0)
            return &rs[i];
    return NULL;
}

static void print_reference(const result *rs, int32_t nr)
{
    int any = 0;
    for (size_t i = 0; i < sizeof REFERENCES / sizeof REFERENCES[0]; i++) {
        const reference *ref = &REFERENCES[i];
        const result *r = find(rs, nr, ref->scene, ref->n, "rigid");
        if (r == NULL) continue;
        if (!any) {
            printf("\nagainst the issue's figures: ms/step; Box2D 2.4 and Chipmunk 7 measured in this run "
                   "(when built), Box2D v3.2 QUOTED from the issue (its median), not measured.\n"
                   "median is the issue's figure; mean over all steps; settling: mean until the "
                   "pile rests (all steps when it never does)\n");
            printf("%-6s %6s %-9s %9s %9s %9s %8s %11s %11s %11s %11s\n", "scene", "N", "figure",
                   "rigid", "box2d2.4", "chipmunk7", "v3.2(q)", "rigid/b2.4", "rigid/cp7",
                   "rigid/v3(q)", "v3(q)/rigid");
            any = 1;
        }
        const result *b = find(rs, nr, ref->scene, ref->n, "box2d");
        const result *c = find(rs, nr, ref->scene, ref->n, "chipmunk");
        for (int f = 0; f < 3; f++) {
            static const char *const names[3] = { "median", "mean", "settling" };
            double rv = f == 0 ? r->median : f == 1 ? r->mean : r->settling;
            char bs[16] = "-", cs[16] = "-", br[16] = "-", cr[16] = "-", v3[16] = "", v3r[16] = "",
                 v3s[16] = "";
            if (b != NULL) {
                double bv = f == 0 ? b->median : f == 1 ? b->mean : b->settling;
                snprintf(bs, sizeof bs, "%.3f", bv);
                snprintf(br, sizeof br, "%.3f", rv / bv);
            }
            if (c != NULL) {
                double cv = f == 0 ? c->median : f == 1 ? c->mean : c->settling;
                snprintf(cs, sizeof cs, "%.3f", cv);
                snprintf(cr, sizeof cr, "%.3f", rv / cv);
            }
            if (f == 0) {
                snprintf(v3, sizeof v3, "%.2f", ref->box2d_v3);
                snprintf(v3r, sizeof v3r, "%.3f", rv / ref->box2d_v3);
                snprintf(v3s, sizeof v3s, "%.1fx", ref->box2d_v3 / rv);
            }
            char ns[16] = "";
            if (f == 0) snprintf(ns, sizeof ns, "%d", (int)ref->n);
            printf("%-6s %6s %-9s %9.3f %9s %9s %8s %11s %11s %11s %11s\n", f == 0 ? ref->scene : "",
                   ns, names[f], rv, bs, cs, v3, br, cr, v3r, v3s);
        }
        printf("%-6s %6s %-9s %9s %9.1f %9.1f   (the issue's Box2D 2.4.1 / Chipmunk 7.0.3 medians)\n",
               "", "", "issue", "", ref->box2d24, ref->chipmunk7);
    }
}

/* No allocation in a steady-state step: rigid's allocator calls in the second half. */
static void print_allocs(const result *rs, int32_t nr)
{
    int any = 0, nonzero = 0;
    for (int32_t i = 0; i < nr; i++) {
        if (!rs[i].ok || rs[i].steady_allocs < 0 || rs[i].engine != &bench_rigid_engine) continue;
        if (!any) printf("\nrigid's allocator calls in the second half of each run (steady state):");
        any = 1;
        if (rs[i].steady_allocs > 0) {
            printf(" %s %d: %lld;", rs[i].scene, (int)rs[i].n, (long long)rs[i].steady_allocs);
            nonzero = 1;
        }
    }
    if (any) printf("%s\n", nonzero ? "" : " none in any scene");
}

/* What the step costs for stages a scene does not use: should be (about) nothing. */
static void print_stage_costs(const result *rs, int32_t nr)
{
    const result *sp = find(rs, nr, "sparse", 0, "rigid");
    const result *fd = find(rs, nr, "free0", 0, "rigid");
    const result *fn = find(rs, nr, "free-nodrag", 0, "rigid");
    const result *fl = find(rs, nr, "free-nodrag", 0, "floor");
    const result *fld = find(rs, nr, "free0", 0, "floor");
    if (sp == NULL && fn == NULL) return;
    printf("\nstage costs (rigid; a stage nobody uses should cost nothing):\n");
    if (fn != NULL && fd != NULL && fd->n == fn->n)
        printf("  drag: free0 (linear drag on every body) %.3f ns/body-step; free-nodrag (none set) "
               "%.3f ns/body-step\n", fd->ns_body, fn->ns_body);
    if (fn != NULL && fl != NULL && fl->n == fn->n)
        printf("  free-nodrag %.3f ns/body-step vs the floor loop (x, y, vx, vy only) %.3f: %.2fx\n",
               fn->ns_body, fl->ns_body, fn->ns_body / fl->ns_body);
    if (fd != NULL && fld != NULL && fld->n == fd->n)
        printf("  free0 %.3f ns/body-step vs the floor loop with drag %.3f: %.2fx\n", fd->ns_body,
               fld->ns_body, fd->ns_body / fld->ns_body);
    if (sp != NULL && fn != NULL) {
        /* Means, not medians: the 1% settle and may sleep, which a median hides. */
        int32_t shaped = sp->n / 100 > 0 ? sp->n / 100 : 1;
        const result *rain = find(rs, nr, "rain", shaped, "rigid");
        double particles = fn->mean * (double)(sp->n - shaped) / fn->n;
        printf("  sparse %d (1%% shaped): mean %.3f ms/step; its %d shape-less bodies at free-nodrag's "
               "rate: %.3f ms; so the 1%% with collision: %.3f ms",
               (int)sp->n, sp->mean, (int)(sp->n - shaped), particles, sp->mean - particles);
        if (rain != NULL)
            printf(" vs rain %d alone: mean %.3f ms (%.2fx)\n", (int)shaped, rain->mean,
                   (sp->mean - particles) / rain->mean);
        else
            printf(" (run rain:%d to compare)\n", (int)shaped);
    }
}

/* The gameplay variants against their plain scenes (tools/bench_gameplay.c). */
static void print_gameplay(const result *rs, int32_t nr)
{
    bench_gameplay_row *rows = calloc((size_t)(nr > 0 ? nr : 1), sizeof *rows);
    int32_t n = 0;
    if (rows == NULL) return;
    for (int32_t i = 0; i < nr; i++) {
        const result *r = &rs[i];
        if (!r->ok || r->engine != &bench_rigid_engine) continue;
        rows[n++] = (bench_gameplay_row){ r->scene, r->def->base != NULL ? r->def->base : r->scene,
                                          r->n, r->def->variant, r->median, r->min_median,
                                          r->max_median, r->contacts };
    }
    bench_gameplay_report(rows, n);
    free(rows);
}

/* ---------------------------------------------------------------- main */

typedef struct job {
    const scene_def *def;
    int32_t n;
} job;

static void usage(FILE *f)
{
    fprintf(f, "usage: bench [--quick] [--scene NAME[:N,N...]]... [--engine a,b,...] [--steps S]\n"
               "             [--repeats R] [--csv FILE] [--dump FILE] [--list]\n"
               "  --quick     a smoke run: small sizes, 60 steps, 1 run\n"
               "  --scene     a scene, optionally with sizes (default: every scene, default sizes)\n"
               "  --engine    among:");
    for (int i = 0; i < NENGINES; i++) fprintf(f, " %s", ENGINES[i]->name);
    fprintf(f, " (default: all)\n"
               "  --steps     steps per run (default 600)\n"
               "  --repeats   runs per scene and engine; figures are medians over runs (default 3)\n"
               "  --csv       also write the results as CSV\n"
               "  --dump      write the final state of every dynamic body of every run (CSV)\n");
}

int main(int argc, char **argv)
{
    int quick = 0;
    int32_t steps = 0, repeats = 0;
    const char *csv = NULL, *engines_arg = NULL;
    job jobs[64];
    int32_t njobs = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--quick") == 0) {
            quick = 1;
        } else if (strcmp(a, "--list") == 0) {
            for (int k = 0; k < NSCENES; k++)
                printf("%-20s %s (default N:%d%s%s)\n", SCENES[k].name, SCENES[k].what,
                       (int)SCENES[k].default_sizes[0], SCENES[k].default_sizes[1] ? "," : "",
                       SCENES[k].default_sizes[1] ? "..." : "");
            return 0;
        } else if ((strcmp(a, "--steps") == 0 || strcmp(a, "--repeats") == 0) && i + 1 < argc) {
            long v = strtol(argv[++i], NULL, 10);
            if (v < 1 || v > 1000000) {
                fprintf(stderr, "bench: %s wants a positive number\n", a);
                return 2;
            }
            if (a[2] == 's') steps = (int32_t)v;
            else repeats = (int32_t)(v > 64 ? 64 : v);
        } else if (strcmp(a, "--csv") == 0 && i + 1 < argc) {
            csv = argv[++i];
        } else if (strcmp(a, "--dump") == 0 && i + 1 < argc) {
            dump_file = fopen(argv[++i], "w");
            if (dump_file == NULL) {
                perror(argv[i]);
                return 1;
            }
            fprintf(dump_file, "scene,n,engine,k,x,y,vx,vy\n");
        } else if (strcmp(a, "--engine") == 0 && i + 1 < argc) {
            engines_arg = argv[++i];
        } else if (strcmp(a, "--scene") == 0 && i + 1 < argc) {
            char name[64];
            const char *arg = argv[++i], *colon = strchr(arg, ':');
            size_t len = colon != NULL ? (size_t)(colon - arg) : strlen(arg);
            if (len >= sizeof name) len = sizeof name - 1;
            memcpy(name, arg, len);
            name[len] = 0;
            const scene_def *d = scene_find(name);
            if (d == NULL) {
                fprintf(stderr, "bench: unknown scene '%s' (--list)\n", name);
                return 2;
            }
            if (colon == NULL) {
                for (int k = 0; k < 4 && d->default_sizes[k] > 0 && njobs < 64; k++)
                    jobs[njobs++] = (job){ d, d->default_sizes[k] };
            } else {
                const char *p = colon + 1;
                while (*p != 0 && njobs < 64) {
                    char *end;
                    long v = strtol(p, &end, 10);
                    if (end == p || v < 1 || v > 10000000) {
                        fprintf(stderr, "bench: bad size in '%s'\n", arg);
                        return 2;
                    }
                    jobs[njobs++] = (job){ d, (int32_t)v };
                    p = *end == ',' ? end + 1 : end;
                    if (*end != ',' && *end != 0) {
                        fprintf(stderr, "bench: bad size list in '%s'\n", arg);
                        return 2;
                    }
                }
            }
        } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else {
            usage(stderr);
            return 2;
        }
    }
    if (steps == 0) steps = quick ? 60 : 600;
    if (repeats == 0) repeats = quick ? 1 : 3;
    if (njobs == 0)
        for (int k = 0; k < NSCENES; k++) {
            if (quick) {
                jobs[njobs++] = (job){ &SCENES[k], SCENES[k].quick_size };
                continue;
            }
            for (int m = 0; m < 4 && SCENES[k].default_sizes[m] > 0; m++)
                jobs[njobs++] = (job){ &SCENES[k], SCENES[k].default_sizes[m] };
        }
    const bench_engine *engines[8];
    int nengines = 0;
    for (int i = 0; i < NENGINES; i++) {
        if (engines_arg != NULL) {
            const char *p = strstr(engines_arg, ENGINES[i]->name);
            size_t len = strlen(ENGINES[i]->name);
            if (p == NULL || (p != engines_arg && p[-1] != ',') || (p[len] != 0 && p[len] != ','))
                continue;
        }
        engines[nengines++] = ENGINES[i];
    }
    if (nengines == 0) {
        fprintf(stderr, "bench: no such engine in '%s'\n", engines_arg);
        return 2;
    }

    const char *versions[8];
    for (int i = 0; i < nengines; i++) versions[i] = engines[i]->version(); /* banners first */
    fflush(stderr);
    printf("rigid bench: dt = 1/60 s, %d steps per run, %d run(s) per scene and engine, single "
           "thread; figures are medians over runs\n", (int)steps, (int)repeats);
    machine(stdout);
    printf("engines:");
    for (int i = 0; i < nengines; i++) printf(" [%s]", versions[i]);
    printf("\n");
#ifndef RG_BENCH_PEERS
    printf("(built without the peers: `make bench` builds them when libbox2d-dev and "
           "libchipmunk-dev are installed)\n");
#endif
    printf("ns/body-step counts dynamic bodies; B/body: bytes held at the end over all bodies incl. "
           "static (rigid: its allocator's count, peak in the CSV; peers: heap growth)\n"
           "overlap: deepest between two moving bodies; wall: a moving body into a static shape; "
           "vmax at the end; rest: s until the fastest body stays < %.1f m/s\n\n", REST_SPEED);
    print_header();
    fflush(stdout);

    FILE *cf = NULL;
    if (csv != NULL) {
        cf = fopen(csv, "w");
        if (cf == NULL) {
            perror(csv);
            return 1;
        }
        csv_header(cf);
    }

    result *results = calloc((size_t)njobs * (size_t)nengines, sizeof *results);
    run_result *runs = calloc((size_t)repeats * (size_t)nengines, sizeof *runs);
    double *times = malloc((size_t)steps * sizeof *times);
    if (results == NULL || runs == NULL || times == NULL) return 1;
    int32_t nres = 0;
    for (int32_t j = 0; j < njobs; j++) {
        bench_scene s;
        if (!scene_build(&s, jobs[j].def, jobs[j].n)) return 1;
        state_buf st;
        size_t nd = (size_t)(s.ndynamic > 0 ? s.ndynamic : 1);
        st.x = malloc(4 * nd * sizeof(float));
        if (st.x == NULL) return 1;
        st.y = st.x + nd;
        st.vx = st.y + nd;
        st.vy = st.vx + nd;
        memset(runs, 0, (size_t)repeats * (size_t)nengines * sizeof *runs);
        /* a gameplay variant runs on rigid only */
        const int rigid_only = jobs[j].def->variant != BENCH_PLAIN;
        for (int32_t rep = 0; rep < repeats; rep++)
            for (int e = 0; e < nengines; e++)
                if (!rigid_only || engines[e] == &bench_rigid_engine)
                    runs[e * repeats + rep] = run_once(engines[e], &s, jobs[j].def, steps, times,
                                                       &st);
        const result *rigid = NULL;
        for (int e = 0; e < nengines; e++) {
            if (rigid_only && engines[e] != &bench_rigid_engine) continue;
            result *r = &results[nres++];
            r->def = jobs[j].def;
            snprintf(r->scene, sizeof r->scene, "%s", s.name);
            r->n = s.size;
            r->engine = engines[e];
            r->nbodies = s.nbodies;
            r->ndynamic = s.ndynamic;
            r->steps = steps;
            combine(r, &runs[e * repeats], repeats);
            if (engines[e] == &bench_rigid_engine) rigid = r;
            if (engines[e] == &floor_engine && !r->ok) continue; /* floor only runs free scenes */
            print_result(r, rigid);
            if (cf != NULL) csv_row(cf, r);
        }
        fflush(stdout);
        free(st.x);
        free(s.bodies);
    }
    print_reference(results, nres);
    print_stage_costs(results, nres);
    print_gameplay(results, nres);
    print_allocs(results, nres);
    printf("\n");
    machine(stdout);
    if (cf != NULL) fclose(cf);
    if (dump_file != NULL) fclose(dump_file);
    free(results);
    free(runs);
    free(times);
    return 0;
}
