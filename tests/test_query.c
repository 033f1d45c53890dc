/* test_query.c: raycasts, every hit along a ray, shape casts, box and point queries against
 * the shapes as they are now. */
#include "testutil.h"

static void test_query_arguments_are_checked(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_ray_hit hit;
    hit.body = 77;
    assert_int_equal(rg_world_raycast(w, v2(NAN, 0), v2(1, 0), 1, &hit), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(INFINITY, 0), 1, &hit), RG_ERR_INVALID_ARGUMENT);
    assert_true(hit.body == 77);
    rg_body out[2];
    assert_int_equal(rg_world_query_aabb(w, v2(0, NAN), v2(1, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(INFINITY, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(2, 0), v2(1, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 2), v2(1, 1), 1, out, 2), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(1, 1), 1, out, -1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(1, 1), 1, NULL, 1), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_aabb(w, v2(0, 0), v2(1, 1), 1, NULL, 0), 0);
    rg_world_destroy(w);
}

static void test_raycast_finds_the_closest_shape_with_point_normal_and_fraction(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body near_box = box_body(w, RG_BODY_STATIC, 0, 5, 0, 1, 1);
    rg_body far_ball = circle_body(w, RG_BODY_DYNAMIC, 1, 10, 0, 1);
    rg_body side = circle_body(w, RG_BODY_DYNAMIC, 1, 2, 3, 0.5);
    (void)side;
    rg_ray_hit hit;
    /* before any step */
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(20, 0), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == near_box);
    assert_near(hit.fraction, 4.0 / 20, 1e-6);
    assert_near(hit.point.x, 4, 1e-5);
    assert_near(hit.normal.x, -1, 0);
    assert_near(hit.normal.y, 0, 0);
    /* masked out: the ball behind it */
    assert_ok(rg_body_set_filter(w, near_box, 2, 0xFFFFFFFFu));
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(20, 0), 1, &hit), 1);
    assert_true(hit.body == far_ball);
    assert_near(hit.point.x, 9, 1e-5);
    /* too short, and nothing at all */
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(3, 0), 0xFFFFFFFFu, &hit), 0);
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(0, -20), 0xFFFFFFFFu, &hit), 0);
    /* from inside the box: the box is ignored, the ball is hit */
    assert_int_equal(rg_world_raycast(w, v2(5, 0), v2(20, 0), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == far_ball);
    /* at an angle onto the ball: normal from its centre */
    assert_int_equal(rg_world_raycast(w, v2(10, 5), v2(0, -10), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == far_ball);
    assert_near(hit.point.y, 1, 1e-5);
    assert_near(hit.normal.y, 1, 1e-6);
    /* a teleported body is seen where it is now */
    assert_ok(rg_body_set_position(w, far_ball, v2(10, 50)));
    assert_int_equal(rg_world_raycast(w, v2(10, 5), v2(0, -10), 0xFFFFFFFFu, &hit), 0);
    rg_world_destroy(w);
}

static void test_raycast_ties_go_to_the_lower_handle_and_long_rays_work(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body a = box_body(w, RG_BODY_STATIC, 0, 5000, 1, 1, 1), b = box_body(w, RG_BODY_STATIC, 0, 5000, -1, 1, 1);
    for (int i = 0; i < 200; i++) box_body(w, RG_BODY_STATIC, 0, i * 3.0, 10, 0.5, 0.5);
    rg_ray_hit hit;
    assert_int_equal(rg_world_raycast(w, v2(0, 0), v2(10000, 0), 0xFFFFFFFFu, &hit), 1);
    assert_true(hit.body == (a < b ? a : b));
    assert_near(hit.point.x, 4999, 0.01);
    rg_world_destroy(w);
}

static void test_aabb_query_returns_sorted_handles_and_the_full_count(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b[10];
    for (int i = 0; i < 10; i++) b[i] = circle_body(w, RG_BODY_DYNAMIC, 1, i, 0, 0.25);
    rg_body none = make_body(w, 1, 3, 0); /* no shape: never found */
    (void)none;
    assert_ok(rg_body_set_sensor(w, b[4], 1));         /* sensors are found */
    assert_ok(rg_body_set_filter(w, b[5], 8, 0xFFFFFFFFu)); /* masked out below */
    rg_body out[10];
    /* circle i spans [i - 0.25, i + 0.25]: the box [2.25, 5.75] touches circles 2 and 6 at
     * their edges and overlaps 3, 4, 5; 5 is masked out, the sensor 4 is found */
    int32_t n = rg_world_query_aabb(w, v2(2.25, -1), v2(5.75, 1), 1, out, 10);
    assert_int_equal(n, 4);
    rg_body expect[4] = {b[2], b[3], b[4], b[6]};
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            if (expect[j] < expect[i]) {
                rg_body t = expect[i];
                expect[i] = expect[j];
                expect[j] = t;
            }
    assert_memory_equal(out, expect, sizeof expect);
    rg_world_destroy(w);
}

static void test_aabb_query_counts_beyond_capacity_and_sees_teleports(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body b[20];
    for (int i = 0; i < 20; i++) b[i] = box_body(w, i % 2 ? RG_BODY_STATIC : RG_BODY_DYNAMIC, 1, i, 0, 0.4, 0.4);
    rg_body out[20];
    assert_int_equal(rg_world_query_aabb(w, v2(-1, -1), v2(30, 1), 0xFFFFFFFFu, out, 20), 20);
    for (int k = 1; k < 20; k++) assert_true(out[k - 1] < out[k]);
    rg_body few[3];
    assert_int_equal(rg_world_query_aabb(w, v2(-1, -1), v2(30, 1), 0xFFFFFFFFu, few, 3), 20);
    /* the three smallest handles */
    assert_memory_equal(few, out, sizeof few);
    assert_int_equal(rg_world_query_aabb(w, v2(-1, -1), v2(30, 1), 0xFFFFFFFFu, NULL, 0), 20);
    /* masks and teleports */
    assert_ok(rg_body_set_filter(w, b[3], 2, 0xFFFFFFFFu));
    assert_int_equal(rg_world_query_aabb(w, v2(2.5, -1), v2(3.5, 1), 1, out, 20), 0);
    assert_int_equal(rg_world_query_aabb(w, v2(2.5, -1), v2(3.5, 1), 2, out, 20), 1);
    assert_ok(rg_body_set_position(w, b[3], v2(100, 100)));
    assert_int_equal(rg_world_query_aabb(w, v2(99, 99), v2(101, 101), 0xFFFFFFFFu, out, 20), 1);
    assert_true(out[0] == b[3]);
    /* exactly touching edges count */
    assert_int_equal(rg_world_query_aabb(w, v2(0.4, -1), v2(0.4, 1), 0xFFFFFFFFu, out, 20), 1);
    assert_true(out[0] == b[0]);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- every hit along a ray */

static uint64_t qseed = 88172645463325252ull;
static double qrand(void)
{
    qseed ^= qseed << 13;
    qseed ^= qseed >> 7;
    qseed ^= qseed << 17;
    return (double)(qseed >> 11) * 0x1p-53;
}

typedef struct ref_shape {
    rg_body h;
    int circle;
    double x, y, hx, hy;
} ref_shape;

/* The entry fraction of the ray o + t d, t in [0, 1], into the shape, written independently
 * of the library: the quadratic for a circle, the slab test for a box; -1 for a miss or an
 * origin inside the shape. */
static double ref_entry(const ref_shape *s, double ox, double oy, double dx, double dy)
{
    double qx = ox - s->x, qy = oy - s->y;
    if (s->circle) {
        double a = dx * dx + dy * dy, b = 2 * (qx * dx + qy * dy), c = qx * qx + qy * qy - s->hx * s->hx;
        if (c <= 0) return -1;
        double disc = b * b - 4 * a * c;
        if (disc < 0 || a == 0) return -1;
        double t = (-b - sqrt(disc)) / (2 * a);
        return t >= 0 && t <= 1 ? t : -1;
    }
    if (fabs(qx) <= s->hx && fabs(qy) <= s->hy) return -1;
    double t0 = 0, t1 = 1;
    double q[2] = { qx, qy }, d[2] = { dx, dy }, e[2] = { s->hx, s->hy };
    for (int k = 0; k < 2; k++) {
        if (d[k] == 0) {
            if (fabs(q[k]) > e[k]) return -1;
            continue;
        }
        double ta = (-e[k] - q[k]) / d[k], tb = (e[k] - q[k]) / d[k];
        if (ta > tb) { double t = ta; ta = tb; tb = t; }
        if (ta > t0) t0 = ta;
        if (tb < t1) t1 = tb;
        if (t0 > t1) return -1;
    }
    return t0;
}

/* Random scenes of 300 circles and boxes of sizes 0.05-3 m in 100 m; random rays of every
 * length: the same shapes as brute force, in order of fraction then handle, with the
 * fractions within rounding; capacity keeps the first ones. */
static void test_raycast_all_matches_brute_force_on_random_scenes(void **state)
{
    (void)state;
    enum { N = 300, RAYS = 400 };
    static ref_shape ref[N];
    static rg_ray_hit hits[N], few[5];
    for (int scene = 0; scene < 3; scene++) {
        rg_world *w = gravity_world(0);
        for (int i = 0; i < N; i++) {
            ref_shape *s = &ref[i];
            s->circle = qrand() < 0.5;
            s->x = qrand() * 100 - 50;
            s->y = qrand() * 100 - 50;
            s->hx = 0.05 + qrand() * 3;
            s->hy = s->circle ? s->hx : 0.05 + qrand() * 3;
            s->h = s->circle ? circle_body(w, RG_BODY_STATIC, 0, s->x, s->y, s->hx)
                             : box_body(w, RG_BODY_STATIC, 0, s->x, s->y, s->hx, s->hy);
            s->x = (double)(rg_real)s->x;
            s->y = (double)(rg_real)s->y;
            s->hx = (double)(rg_real)s->hx;
            s->hy = (double)(rg_real)s->hy;
        }
        for (int r = 0; r < RAYS; r++) {
            double ox = qrand() * 120 - 60, oy = qrand() * 120 - 60;
            double len = r % 4 == 0 ? 200 : r % 4 == 1 ? 20 : 3;
            double ang = qrand() * 6.283185307179586;
            double dx = (double)(rg_real)(cos(ang) * len), dy = (double)(rg_real)(sin(ang) * len);
            ox = (double)(rg_real)ox;
            oy = (double)(rg_real)oy;
            int32_t n = rg_world_raycast_all(w, v2(ox, oy), v2(dx, dy), 0xFFFFFFFFu, hits, N);
            assert_true(n >= 0 && n <= N);
            int expect = 0;
            double tol = 1e-5 * len + 1e-4;
            for (int i = 0; i < N; i++) {
                double t = ref_entry(&ref[i], ox, oy, dx, dy);
                int found = -1;
                for (int k = 0; k < n; k++)
                    if (hits[k].body == ref[i].h) found = k;
                if (t >= 0) {
                    expect++;
                    /* a ray grazing a shape within rounding may go either way */
                    if (found < 0) {
                        double tm = ref_entry(&ref[i], ox + dy * tol, oy - dx * tol, dx, dy);
                        double tp = ref_entry(&ref[i], ox - dy * tol, oy + dx * tol, dx, dy);
                        assert_true(tm < 0 || tp < 0 || t > 1 - tol);
                        expect--;
                        continue;
                    }
                    assert_near(hits[found].fraction, t, tol / len);
                } else if (found >= 0) {
                    expect++; /* the library saw a graze the reference missed: only within rounding */
                    double t2 = ref_entry(&ref[i], ox + dy * tol, oy - dx * tol, dx, dy);
                    double t3 = ref_entry(&ref[i], ox - dy * tol, oy + dx * tol, dx, dy);
                    assert_true(t2 >= 0 || t3 >= 0 || (double)hits[found].fraction >= 1 - tol);
                }
            }
            assert_int_equal(n, expect);
            for (int k = 1; k < n; k++)
                assert_true(hits[k - 1].fraction < hits[k].fraction ||
                            (hits[k - 1].fraction == hits[k].fraction && hits[k - 1].body < hits[k].body));
            int32_t m = rg_world_raycast_all(w, v2(ox, oy), v2(dx, dy), 0xFFFFFFFFu, few, 5);
            assert_int_equal(m, n);
            for (int k = 0; k < n && k < 5; k++) assert_true(few[k].body == hits[k].body);
            /* the closest of them is what rg_world_raycast gives */
            rg_ray_hit one;
            assert_int_equal(rg_world_raycast(w, v2(ox, oy), v2(dx, dy), 0xFFFFFFFFu, &one), n > 0);
            if (n > 0) assert_true(one.body == hits[0].body && one.fraction == hits[0].fraction);
        }
        rg_world_destroy(w);
    }
}

static void test_query_point_includes_edges_and_uses_the_mask(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body ball = circle_body(w, RG_BODY_STATIC, 0, 0, 0, 1);
    rg_body box = box_body(w, RG_BODY_STATIC, 0, 3, 0, 1, 0.5);
    rg_body coin = circle_body(w, RG_BODY_STATIC, 0, 3.5, 0.25, 0.5);
    assert_ok(rg_body_set_sensor(w, coin, 1));
    assert_ok(rg_body_set_filter(w, coin, 4, 0xFFFFFFFFu));
    rg_body out[4];
    assert_int_equal(rg_world_query_point(w, v2(1, 0), 0xFFFFFFFFu, out, 4), 1);       /* on the circle */
    assert_true(out[0] == ball);
    assert_int_equal(rg_world_query_point(w, v2(0, -1), 0xFFFFFFFFu, out, 4), 1);
    assert_int_equal(rg_world_query_point(w, v2(1.0001, 0), 0xFFFFFFFFu, out, 4), 0);
    assert_int_equal(rg_world_query_point(w, v2(0.71, 0.71), 0xFFFFFFFFu, out, 4), 0);  /* r = 1.004 */
    assert_int_equal(rg_world_query_point(w, v2(0.7, 0.7), 0xFFFFFFFFu, out, 4), 1);    /* r = 0.99 */
    assert_int_equal(rg_world_query_point(w, v2(2, -0.5), 0xFFFFFFFFu, out, 4), 1);    /* box corner */
    assert_true(out[0] == box);
    assert_int_equal(rg_world_query_point(w, v2(4.0001, 0), 0xFFFFFFFFu, out, 4), 0);
    /* the box and the sensor overlap at (3.5, 0.25): both, in handle order; the mask filters */
    assert_int_equal(rg_world_query_point(w, v2(3.5, 0.25), 0xFFFFFFFFu, out, 4), 2);
    assert_true(out[0] == box && out[1] == coin);
    assert_int_equal(rg_world_query_point(w, v2(3.5, 0.25), 4, out, 4), 1);
    assert_true(out[0] == coin);
    assert_int_equal(rg_world_query_point(w, v2(3.5, 0.25), 0xFFFFFFFFu, out, 1), 2);
    assert_true(out[0] == box);
    assert_int_equal(rg_world_query_point(w, v2(3.5, 0.25), 0xFFFFFFFFu, NULL, 0), 2);
    assert_int_equal(rg_world_query_point(NULL, v2(0, 0), 1, out, 4), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_point(w, v2(NAN, 0), 1, out, 4), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_point(w, v2(0, 0), 1, NULL, 4), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_query_point(w, v2(0, 0), 1, out, -2), RG_ERR_INVALID_ARGUMENT);
    rg_world_destroy(w);
}

/* ---------------------------------------------------------------- shape casts */

/* Times of impact against the exact sweep, solved by hand: face contacts are linear in t,
 * a circle against a box corner is the root of |p(t) - corner| = r. */
static void test_cast_shape_time_of_impact_matches_the_exact_sweep(void **state)
{
    (void)state;
    rg_world *w = gravity_world(0);
    rg_body slab = box_body(w, RG_BODY_STATIC, 0, 0, 0.5, 2, 0.5);   /* top y = 1, x in -2..2 */
    rg_body ball = circle_body(w, RG_BODY_STATIC, 0, 10, 1, 1);
    rg_ray_hit h;
    /* a circle r 0.5 falling onto the slab's top: 5 - 0.5 - 1 = 3.5 of 10 */
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(0, 5), v2(0, -10), 0xFFFFFFFFu, &h), 1);
    assert_true(h.body == slab);
    assert_near(h.fraction, 0.35, 1e-6);
    assert_near(h.normal.x, 0, 1e-6);
    assert_near(h.normal.y, 1, 1e-6);
    assert_near(h.point.y, 1, 1e-5);
    /* a box 0.5 x 0.5 sliding left into the circle: its face reaches x = 11 - 0.5, i.e. its
     * centre x = 11.5, from 15 over 10: 0.35 */
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_AABB, v2(0.5, 0.5), v2(15, 1), v2(-10, 0), 0xFFFFFFFFu, &h), 1);
    assert_true(h.body == ball);
    assert_near(h.fraction, 0.35, 1e-6);
    assert_near(h.normal.x, 1, 1e-6);
    /* a circle r 0.5 moving left at height y = 1.25 onto the slab's top-right corner (2, 1):
     * centre (x, 1.25) meets the corner when (x - 2)^2 + 0.25^2 = 0.25, x = 2 + sqrt(0.1875) */
    double xc = 2 + sqrt(0.1875);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(6, 1.25), v2(-20, 0), 0xFFFFFFFFu, &h), 1);
    assert_true(h.body == slab);
    assert_near(h.fraction, (6 - xc) / 20, 1e-6);
    /* the contact is on the corner; the normal points from it to the centre */
    assert_near(h.normal.x, (xc - 2) / 0.5, 1e-4);
    assert_near(h.normal.y, 0.25 / 0.5, 1e-4);
    /* nothing in the way */
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(0, 5), v2(0, 3), 0xFFFFFFFFu, &h), 0);
    /* the mask */
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(0, 5), v2(0, -10), 2, &h), 0);
    /* resting on the slab (overlap at the start): casting along it or away is no hit,
     * casting into it is a hit at 0 */
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_AABB, v2(0.5, 0.5), v2(0, 1.5), v2(1, 0), 0xFFFFFFFFu, &h), 0);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_AABB, v2(0.5, 0.5), v2(0, 1.5), v2(0, 2), 0xFFFFFFFFu, &h), 0);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_AABB, v2(0.5, 0.5), v2(0, 1.5), v2(0.5, -1), 0xFFFFFFFFu, &h), 1);
    assert_true(h.fraction == 0 && h.body == slab);
    /* bad input */
    assert_int_equal(rg_world_cast_shape(w, 7, v2(0.5, 0), v2(0, 5), v2(0, -10), 1, &h), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(-1, 0), v2(0, 5), v2(0, -10), 1, &h), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_AABB, v2(1, 0), v2(0, 5), v2(0, -10), 1, &h), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_AABB, v2(1, 1e9), v2(0, 5), v2(0, -10), 1, &h), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(NAN, 5), v2(0, -10), 1, &h), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(0, 5), v2(0, INFINITY), 1, &h), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_cast_shape(w, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(0, 5), v2(0, -10), 1, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rg_world_cast_shape(NULL, RG_SHAPE_CIRCLE, v2(0.5, 0), v2(0, 5), v2(0, -10), 1, &h), RG_ERR_INVALID_ARGUMENT);
    rg_world_destroy(w);
}

/* Random casts against random scenes: the first hit is no later than every shape's own exact
 * time of impact (found by bisection of the overlap test along the path) and equal to the
 * least of them. */
static int ref_overlap(const ref_shape *s, int circle, double x, double y, double hx, double hy)
{
    double dx = fabs(x - s->x), dy = fabs(y - s->y);
    if (!circle && !s->circle) return dx <= hx + s->hx && dy <= hy + s->hy;
    if (circle && s->circle) return dx * dx + dy * dy <= (hx + s->hx) * (hx + s->hx);
    /* circle (radius r at distance d from the box) against a box */
    double bx = circle ? s->hx : hx, by = circle ? s->hy : hy, r = circle ? hx : s->hx;
    double ex = fmax(dx - bx, 0), ey = fmax(dy - by, 0);
    return ex * ex + ey * ey <= r * r;
}

static void test_cast_shape_agrees_with_bisection_on_random_scenes(void **state)
{
    (void)state;
    enum { N = 120, CASTS = 300 };
    static ref_shape ref[N];
    rg_world *w = gravity_world(0);
    for (int i = 0; i < N; i++) {
        ref_shape *s = &ref[i];
        s->circle = qrand() < 0.5;
        s->x = (double)(rg_real)(qrand() * 60 - 30);
        s->y = (double)(rg_real)(qrand() * 60 - 30);
        s->hx = (double)(rg_real)(0.1 + qrand() * 2);
        s->hy = s->circle ? s->hx : (double)(rg_real)(0.1 + qrand() * 2);
        s->h = s->circle ? circle_body(w, RG_BODY_STATIC, 0, s->x, s->y, s->hx)
                         : box_body(w, RG_BODY_STATIC, 0, s->x, s->y, s->hx, s->hy);
    }
    int hits = 0;
    for (int c = 0; c < CASTS; c++) {
        int circle = c % 2;
        double hx = (double)(rg_real)(0.1 + qrand()), hy = circle ? hx : (double)(rg_real)(0.1 + qrand());
        double ox = (double)(rg_real)(qrand() * 80 - 40), oy = (double)(rg_real)(qrand() * 80 - 40);
        double dx = (double)(rg_real)(qrand() * 40 - 20), dy = (double)(rg_real)(qrand() * 40 - 20);
        /* skip starts inside a shape */
        int inside = 0;
        for (int i = 0; i < N; i++) inside |= ref_overlap(&ref[i], circle, ox, oy, hx, hy);
        if (inside) continue;
        double best = 2;
        for (int i = 0; i < N; i++) {
            if (!ref_overlap(&ref[i], circle, ox + dx, oy + dy, hx, hy)) {
                /* may still cross it mid-path: sample, then bisect the first crossing */
                int k;
                for (k = 1; k <= 400; k++)
                    if (ref_overlap(&ref[i], circle, ox + dx * k / 400.0, oy + dy * k / 400.0, hx, hy)) break;
                if (k > 400) continue;
                double lo = (k - 1) / 400.0, hi = k / 400.0;
                for (int it = 0; it < 50; it++) {
                    double mid = (lo + hi) / 2;
                    if (ref_overlap(&ref[i], circle, ox + dx * mid, oy + dy * mid, hx, hy)) hi = mid; else lo = mid;
                }
                if (hi < best) best = hi;
            } else {
                double lo = 0, hi = 1;
                for (int it = 0; it < 50; it++) {
                    double mid = (lo + hi) / 2;
                    if (ref_overlap(&ref[i], circle, ox + dx * mid, oy + dy * mid, hx, hy)) hi = mid; else lo = mid;
                }
                if (hi < best) best = hi;
            }
        }
        rg_ray_hit h;
        int32_t got = rg_world_cast_shape(w, circle ? RG_SHAPE_CIRCLE : RG_SHAPE_AABB, v2(hx, circle ? 0 : hy),
                                          v2(ox, oy), v2(dx, dy), 0xFFFFFFFFu, &h);
        double len = sqrt(dx * dx + dy * dy);
        if (best > 1) {
            /* a grazing path may touch within rounding; nothing else */
            if (got == 1) assert_true(h.fraction >= 0);
            continue;
        }
        /* the sampling may miss a graze shorter than 1/400 of the path: the cast may then hit
         * earlier, but never later than the bisected crossing */
        assert_int_equal(got, 1);
        hits++;
        assert_true((double)h.fraction <= best + 1e-5 + 1e-5 / len);
        if (fabs((double)h.fraction - best) > 1e-4) assert_true((double)h.fraction < best);
    }
    assert_true(hits > 50);
    rg_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_query_arguments_are_checked),
        cmocka_unit_test(test_raycast_finds_the_closest_shape_with_point_normal_and_fraction),
        cmocka_unit_test(test_raycast_ties_go_to_the_lower_handle_and_long_rays_work),
        cmocka_unit_test(test_aabb_query_returns_sorted_handles_and_the_full_count),
        cmocka_unit_test(test_aabb_query_counts_beyond_capacity_and_sees_teleports),
        cmocka_unit_test(test_raycast_all_matches_brute_force_on_random_scenes),
        cmocka_unit_test(test_query_point_includes_edges_and_uses_the_mask),
        cmocka_unit_test(test_cast_shape_time_of_impact_matches_the_exact_sweep),
        cmocka_unit_test(test_cast_shape_agrees_with_bisection_on_random_scenes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
