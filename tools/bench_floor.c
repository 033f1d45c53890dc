/* bench_floor.c: the floor reference of the free scenes, an engine of the bench (bench.h). */
#include <stdlib.h>
#include <string.h>

#include "bench.h"

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

const bench_engine bench_floor_engine = {
    .name = "floor", .create = floor_create, .step = floor_step, .force = floor_push,
    .impulse = floor_push, .read = floor_read, .bytes = floor_bytes, .destroy = floor_destroy,
    .version = floor_version,
};
