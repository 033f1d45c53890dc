/* bench_scenes.c: the benchmark's scenes as engine-neutral body lists (tools/bench.h): the
 * issue's container and spawn grid (rain, boxes, and 100,000 boxes as boxes:100000), free
 * particles, a sparse world, a platformer level, sensors, and rigid's gameplay variants.
 * Everything is deterministic: the jitter is a hash of the body's index. */
#define _GNU_SOURCE 1 /* M_PI */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

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

/* name, what, default sizes, quick size, shaped, settles, sleeping both ways, else on/off,
 * gameplay base and variant */
const bench_scene_def bench_scenes[] = {
    { "rain", "circles r 0.5 falling into a container", { 1000, 4000, 10000, 0 },
      1000, 1, 1, 1, 0, NULL, BENCH_PLAIN },
    { "boxes", "unit boxes falling into a container (boxes:100000 is the big one)",
      { 4000, 10000, 0, 0 }, 1000, 1, 1, 1, 0, NULL, BENCH_PLAIN },
    { "free0", "bodies without shapes, gravity + linear drag 0.1*m", { 100000, 0, 0, 0 },
      10000, 0, 0, 0, 0, NULL, BENCH_PLAIN },
    { "free-nodrag", "free0 without drag (a force nobody set)", { 100000, 0, 0, 0 },
      10000, 0, 0, 0, 0, NULL, BENCH_PLAIN },
    { "sparse", "N bodies, 1% of them circles raining in a container", { 100000, 0, 0, 0 },
      10000, 1, 0, 0, 1, NULL, BENCH_PLAIN },
    { "platformer", "N static tiles, 256 walkers pushing and jumping", { 10000, 100000, 0, 0 },
      10000, 1, 0, 0, 1, NULL, BENCH_PLAIN },
    { "sensors", "N static sensor boxes, N/10 circles drifting through", { 10000, 0, 0, 0 },
      2000, 1, 0, 0, 1, NULL, BENCH_PLAIN },
    /* rigid's gameplay collision, sleeping off (tools/bench_gameplay.c) */
    { "rain-awake", "rain, sleeping off (what the two below compare with)", { 4000, 0, 0, 0 },
      1000, 1, 1, 0, 0, "rain", BENCH_AWAKE },
    { "rain-oneway", "rain-awake, floor and walls one-way", { 4000, 0, 0, 0 },
      1000, 1, 1, 0, 0, "rain", BENCH_ONE_WAY },
    { "rain-presolve", "rain-awake, a pre-solve hook keeping every pair", { 4000, 0, 0, 0 },
      1000, 1, 1, 0, 0, "rain", BENCH_PRE_SOLVE },
    { "rain-verlet", "rain-awake under Verlet", { 4000, 0, 0, 0 }, 1000, 1, 1, 0, 0, "rain",
      BENCH_VERLET },
    { "rain-rk4", "rain-awake under RK4", { 4000, 0, 0, 0 }, 1000, 1, 1, 0, 0, "rain", BENCH_RK4 },
    { "boxes-awake", "boxes, sleeping off", { 4000, 0, 0, 0 }, 1000, 1, 1, 0, 0, "boxes",
      BENCH_AWAKE },
    { "boxes-oneway", "boxes-awake, floor and walls one-way", { 4000, 0, 0, 0 },
      1000, 1, 1, 0, 0, "boxes", BENCH_ONE_WAY },
    { "boxes-presolve", "boxes-awake, a pre-solve hook keeping every pair", { 4000, 0, 0, 0 },
      1000, 1, 1, 0, 0, "boxes", BENCH_PRE_SOLVE },
    { "boxes-verlet", "boxes-awake under Verlet", { 4000, 0, 0, 0 }, 1000, 1, 1, 0, 0, "boxes",
      BENCH_VERLET },
    { "boxes-rk4", "boxes-awake under RK4", { 4000, 0, 0, 0 }, 1000, 1, 1, 0, 0, "boxes", BENCH_RK4 },
    { "platformer-awake", "platformer, sleeping off", { 10000, 0, 0, 0 },
      10000, 1, 0, 0, 0, "platformer", BENCH_AWAKE },
    { "platformer-oneway", "platformer-awake, every tile one-way, facing up", { 10000, 0, 0, 0 },
      10000, 1, 0, 0, 0, "platformer", BENCH_ONE_WAY },
    { "platformer-presolve", "platformer-awake, a pre-solve hook keeping every pair",
      { 10000, 0, 0, 0 }, 10000, 1, 0, 0, 0, "platformer", BENCH_PRE_SOLVE },
};
const int bench_nscenes = (int)(sizeof bench_scenes / sizeof bench_scenes[0]);

const bench_scene_def *bench_scene_find(const char *name)
{
    for (int i = 0; i < bench_nscenes; i++)
        if (strcmp(bench_scenes[i].name, name) == 0) return &bench_scenes[i];
    return NULL;
}

int bench_scene_build(bench_scene *s, const bench_scene_def *d, int32_t n)
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
    s->sleep = d->variant == BENCH_PLAIN ? d->sleep_default : 0;
    s->workers = 1;
    return 1;
}
