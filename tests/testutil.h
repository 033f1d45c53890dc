/* testutil.h: what every cmocka test binary of rigid shares. */
#ifndef RG_TESTUTIL_H
#define RG_TESTUTIL_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rigid.h"

#ifdef RG_DOUBLE
#define REAL_EPS ((double)DBL_EPSILON)
#define REAL_MAX DBL_MAX
#else
#define REAL_EPS ((double)FLT_EPSILON)
#define REAL_MAX FLT_MAX
#endif

#define assert_ok(expr) assert_int_equal((expr), RG_OK)
#define assert_status(expr, st) assert_int_equal((expr), (st))
/* |a - b| <= tol, printing both on failure. */
#define assert_near(a, b, tol)                                                            \
    do {                                                                                  \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);                    \
        if (!(fabs(a_ - b_) <= t_)) fail_msg("%s = %.9g, expected %.9g +- %.3g", #a, a_, b_, t_); \
    } while (0)

static inline rg_vec2 v2(rg_real x, rg_real y)
{
    rg_vec2 v;
    v.x = x;
    v.y = y;
    return v;
}

/* A dynamic body of mass m at (x, y). */
static inline rg_body make_body(rg_world *w, double m, double x, double y)
{
    rg_body b = 0;
    assert_ok(rg_body_create(w, RG_BODY_DYNAMIC, (rg_real)m, v2(x, y), &b));
    return b;
}

static inline rg_vec2 pos_of(rg_world *w, rg_body b)
{
    rg_vec2 p;
    assert_ok(rg_body_get_position(w, b, &p));
    return p;
}

static inline rg_vec2 vel_of(rg_world *w, rg_body b)
{
    rg_vec2 v;
    assert_ok(rg_body_get_velocity(w, b, &v));
    return v;
}

/* A world with gravity (0, gy) m/s^2. */
static inline rg_world *gravity_world(double gy)
{
    rg_world *w;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, gy)));
    return w;
}

/* A body of type `type` and mass m at (x, y) with a circle of radius r. */
static inline rg_body circle_body(rg_world *w, int32_t type, double m, double x, double y, double r)
{
    rg_body b;
    assert_ok(rg_body_create(w, type, (rg_real)m, v2(x, y), &b));
    assert_ok(rg_body_set_circle(w, b, (rg_real)r));
    return b;
}

/* A body of type `type` and mass m at (x, y) with a box of half extents hw, hh. */
static inline rg_body box_body(rg_world *w, int32_t type, double m, double x, double y, double hw,
                               double hh)
{
    rg_body b;
    assert_ok(rg_body_create(w, type, (rg_real)m, v2(x, y), &b));
    assert_ok(rg_body_set_aabb(w, b, (rg_real)hw, (rg_real)hh));
    return b;
}

/* ---- collision fixtures */

#define DT (1.0 / 60)

/* A static floor whose top is y = 0, 200 m wide. */
static inline rg_body floor_of(rg_world *w) { return box_body(w, RG_BODY_STATIC, 0, 0, -0.5, 100, 0.5); }

/* Position and velocity components as doubles. */
static inline double PX(rg_world *w, rg_body b) { return (double)pos_of(w, b).x; }
static inline double PY(rg_world *w, rg_body b) { return (double)pos_of(w, b).y; }
static inline double VX(rg_world *w, rg_body b) { return (double)vel_of(w, b).x; }
static inline double VY(rg_world *w, rg_body b) { return (double)vel_of(w, b).y; }

/* n steps of dt seconds. */
static inline void step_n(rg_world *w, int n, double dt)
{
    for (int i = 0; i < n; i++) assert_ok(rg_world_step(w, (rg_real)dt));
}

/* A uniform number in [0, 1) from a 32-bit linear congruential state (the random scenes). */
static inline double next_uniform(uint32_t *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)((*s >> 8) & 0xFFFFFF) / 16777216.0;
}

/* A boolean getter's value (rg_body_is_grounded, rg_body_is_awake, ...). */
static inline int32_t flag(rg_status (*get)(const rg_world *, rg_body, int32_t *), rg_world *w, rg_body b)
{
    int32_t v = -1;
    assert_ok(get(w, b, &v));
    return v;
}

/* The events of the last step or advance, at most cap of them; returns the count. */
static inline int32_t get_events(rg_world *w, rg_contact_event *ev, int32_t cap)
{
    int32_t n = rg_world_get_contact_events(w, ev, cap);
    assert_true(n >= 0);
    return n;
}

/* ---- hashing a run: FNV-1a over count numbers of size bytes (4 or 8) at p, continuing from
 * h, each number's bytes taken least significant first: its bytes in memory on a
 * little-endian machine, and the same on a big-endian one (so a pinned hash holds on both) */
static inline uint64_t fnv(uint64_t h, const void *p, size_t count, size_t size)
{
    const unsigned char *c = p;
    assert_true(size == 4 || size == 8);
    for (size_t i = 0; i < count; i++, c += size) {
        uint64_t v;
        if (size == 4) {
            uint32_t u;
            memcpy(&u, c, 4);
            v = u;
        } else {
            memcpy(&v, c, 8);
        }
        for (size_t k = 0; k < size; k++) h = (h ^ (unsigned char)(v >> (8 * k))) * 1099511628211ull;
    }
    return h;
}

/* Every body's validity and, for live ones, position, velocity, grounded and awake flags,
 * in the order given, hashed onto h. */
static inline uint64_t hash_bodies(rg_world *w, const rg_body *b, int n, uint64_t h)
{
    for (int i = 0; i < n; i++) {
        int32_t valid = rg_body_is_valid(w, b[i]);
        h = fnv(h, &valid, 1, sizeof valid);
        if (!valid) continue;
        rg_vec2 pv[2] = { pos_of(w, b[i]), vel_of(w, b[i]) };
        int32_t flags[2];
        assert_ok(rg_body_is_grounded(w, b[i], &flags[0]));
        assert_ok(rg_body_is_awake(w, b[i], &flags[1]));
        h = fnv(h, pv, 4, sizeof pv[0].x);
        h = fnv(h, flags, 2, sizeof flags[0]);
    }
    return h;
}

/* ---- an allocator that counts, checks sizes, and fails from its Nth allocation on */
typedef struct test_alloc {
    long calls;        /* allocations attempted */
    long fail_at;      /* the allocation (1-based) that fails, and every one after; 0 = never */
    long live_blocks;
    long long live_bytes;
} test_alloc;

static inline void *test_alloc_fn(void *user, void *ptr, size_t old_size, size_t new_size)
{
    test_alloc *t = user;
    if (new_size == 0) {
        if (ptr != NULL) {
            t->live_blocks--;
            t->live_bytes -= (long long)old_size;
            free(ptr);
        }
        return NULL;
    }
    t->calls++;
    if (t->fail_at > 0 && t->calls >= t->fail_at) return NULL;
    void *p = realloc(ptr, new_size);
    if (p == NULL) return NULL;
    if (ptr == NULL) t->live_blocks++;
    t->live_bytes += (long long)new_size - (long long)old_size;
    return p;
}

/* ---- shapes: their gap from positions and sizes, in double */

/* Distance between the surfaces of two bodies' shapes (negative: the depth), in double, from
 * their positions and half extents. */
static inline double surface_gap(rg_world *w, rg_body a, rg_body b)
{
    int32_t ka, kb;
    rg_vec2 ha, hb;
    assert_ok(rg_body_get_shape(w, a, &ka, &ha));
    assert_ok(rg_body_get_shape(w, b, &kb, &hb));
    if (ka == RG_SHAPE_AABB && kb == RG_SHAPE_CIRCLE) return surface_gap(w, b, a);
    rg_vec2 pa = pos_of(w, a), pb = pos_of(w, b);
    double dx = fabs((double)pb.x - (double)pa.x), dy = fabs((double)pb.y - (double)pa.y);
    double hax = (double)ha.x, hay = (double)ha.y, hbx = (double)hb.x, hby = (double)hb.y;
    if (ka == RG_SHAPE_CIRCLE && kb == RG_SHAPE_CIRCLE) return sqrt(dx * dx + dy * dy) - hax - hbx;
    if (ka == RG_SHAPE_AABB) { /* two boxes: the axis of least overlap, or the gap */
        double gx = dx - hax - hbx, gy = dy - hay - hby;
        if (gx <= 0 && gy <= 0) return gx > gy ? gx : gy;
        gx = gx > 0 ? gx : 0;
        gy = gy > 0 ? gy : 0;
        return sqrt(gx * gx + gy * gy);
    }
    /* a circle (a) and a box (b): from the centre to the box, less the radius */
    double qx = dx - hbx, qy = dy - hby;
    if (qx <= 0 && qy <= 0) return (qx > qy ? qx : qy) - hax;
    qx = qx > 0 ? qx : 0;
    qy = qy > 0 ? qy : 0;
    return sqrt(qx * qx + qy * qy) - hax;
}

/* The rounding the library's gap may carry against surface_gap's: some ulps of the
 * coordinates and sizes involved. */
static inline double gap_rounding(rg_world *w, rg_body a, rg_body b)
{
    rg_vec2 pa = pos_of(w, a), pb = pos_of(w, b), ha, hb;
    assert_ok(rg_body_get_shape(w, a, NULL, &ha));
    assert_ok(rg_body_get_shape(w, b, NULL, &hb));
    double scale = fabs((double)pa.x) + fabs((double)pa.y) + fabs((double)pb.x) + fabs((double)pb.y) +
                   (double)ha.x + (double)ha.y + (double)hb.x + (double)hb.y;
    return 64 * REAL_EPS * scale;
}

#endif
