/* test_determinism.c: collision scenes hashed after hundreds of steps and compared with
 * constants pinned for the float and the double build.
 *
 * Any change of code, compiler, optimisation level or SIMD path that alters a single bit of
 * any body's position or velocity, a flag, or an event shows up here.  Update a constant
 * only for an intended change of results, and say in the commit which one and why.  The
 * hash covers bodies by creation order and events by the creation index of their bodies
 * (handles carry a per-world tag, which is no part of the simulation). */
#include "testutil.h"

typedef struct scene {
    rg_world *w;
    rg_body b[256];
    int n;
} scene;

static int index_of(const scene *s, rg_body h)
{
    for (int i = 0; i < s->n; i++)
        if (s->b[i] == h) return i;
    return -1;
}

/* Positions, velocities, grounded and awake flags of every live body; this step's events;
 * the touching and awake counts. */
static uint64_t scene_hash(const scene *s, uint64_t h)
{
    h = hash_bodies(s->w, s->b, s->n, h);
    rg_contact_event ev[512];
    int32_t n = rg_world_get_contact_events(s->w, ev, 512);
    assert_true(n >= 0 && n <= 512);
    for (int32_t k = 0; k < n; k++) {
        int32_t who[4] = { index_of(s, ev[k].a), index_of(s, ev[k].b), ev[k].kind, ev[k].sensor };
        rg_real r[6] = { ev[k].normal.x, ev[k].normal.y, ev[k].point.x, ev[k].point.y, ev[k].depth,
                         ev[k].speed };
        h = fnv(h, who, 4, sizeof who[0]);
        h = fnv(h, r, 6, sizeof r[0]);
    }
    int32_t counts[3] = { n, rg_world_touching_count(s->w), rg_world_awake_body_count(s->w) };
    return fnv(h, counts, 3, sizeof counts[0]);
}

static rg_body add(scene *s, int32_t type, double m, double x, double y)
{
    rg_body b;
    assert_true(s->n < 256);
    assert_ok(rg_body_create(s->w, type, (rg_real)m, v2(x, y), &b));
    s->b[s->n++] = b;
    return b;
}

/* A container, a kinematic platform sweeping across it, 96 circles and boxes of mixed size,
 * mass and material dropped in, a coin sensor, sleeping on: the platform stops at step 320 and
 * by step 600 part of the pile sleeps.  The hash folds in every 40th step. */
static uint64_t run_pile(int32_t integrator)
{
    scene s;
    s.n = 0;
    assert_ok(rg_world_create(&s.w));
    assert_ok(rg_world_set_gravity(s.w, v2(0, -9.81)));
    assert_ok(rg_world_set_integrator(s.w, integrator));
    rg_body floor = add(&s, RG_BODY_STATIC, 0, 0, -0.5);
    assert_ok(rg_body_set_aabb(s.w, floor, 8, 0.5));
    for (int side = -1; side <= 1; side += 2) {
        rg_body wall = add(&s, RG_BODY_STATIC, 0, side * 8.5, 5);
        assert_ok(rg_body_set_aabb(s.w, wall, 0.5, 6));
    }
    rg_body plat = add(&s, RG_BODY_KINEMATIC, 0, -4, 3);
    assert_ok(rg_body_set_aabb(s.w, plat, 1.5, 0.2));
    assert_ok(rg_body_set_velocity(s.w, plat, v2(1.2, 0)));
    rg_body coin = add(&s, RG_BODY_STATIC, 0, 2, 1);
    assert_ok(rg_body_set_circle(s.w, coin, 0.6));
    assert_ok(rg_body_set_sensor(s.w, coin, 1));
    for (int i = 0; i < 96; i++) {
        double x = -6.5 + (i % 12) * 1.1 + 0.013 * (i % 7), y = 5 + (i / 12) * 1.2;
        rg_body b = add(&s, RG_BODY_DYNAMIC, 0.5 + 0.25 * (i % 5), x, y);
        double size = 0.3 + 0.04 * (i % 4);
        if (i % 3 == 0)
            assert_ok(rg_body_set_aabb(s.w, b, (rg_real)size, (rg_real)(size * 0.8)));
        else
            assert_ok(rg_body_set_circle(s.w, b, (rg_real)size));
        if (i % 4 == 1) assert_ok(rg_body_set_restitution(s.w, b, 0.4f));
        if (i % 5 == 2) assert_ok(rg_body_set_friction(s.w, b, 0.2f));
        assert_ok(rg_body_set_velocity(s.w, b, v2((i % 5) - 2, -(i % 3))));
    }
    uint64_t h = 1469598103934665603ull;
    for (int k = 1; k <= 600; k++) {
        if (k == 200) assert_ok(rg_body_set_velocity(s.w, plat, v2(-1.2, 0)));
        if (k == 320) assert_ok(rg_body_set_velocity(s.w, plat, v2(0, 0)));
        assert_ok(rg_world_step(s.w, (rg_real)(1.0 / 60)));
        if (k % 40 == 0) h = scene_hash(&s, h);
    }
    int32_t asleep = s.n - 4 - rg_world_awake_body_count(s.w);
    printf("  (integrator %d: %d bodies asleep)\n", (int)integrator, (int)asleep);
    if (integrator == RG_INTEGRATOR_SEMI_IMPLICIT_EULER && !(asleep > 0)) fail_msg("nothing sleeps"); /* the scene exercises sleeping */
    rg_world_destroy(s.w);
    return h;
}

/* Forces and the accumulator among shapes: springs joining boxes, drag, surface friction,
 * speed limits, wind and gravity scale, stepped through rg_world_advance at jittered frame
 * times; a body teleported, one destroyed, filters and a sensor toggled along the way. */
static uint64_t run_forces(int32_t integrator)
{
    scene s;
    s.n = 0;
    assert_ok(rg_world_create(&s.w));
    assert_ok(rg_world_set_gravity(s.w, v2(0, -9.81)));
    assert_ok(rg_world_set_wind(s.w, v2(0.4, 0)));
    assert_ok(rg_world_set_integrator(s.w, integrator));
    rg_body floor = add(&s, RG_BODY_STATIC, 0, 0, -0.5);
    assert_ok(rg_body_set_aabb(s.w, floor, 20, 0.5));
    for (int i = 0; i < 40; i++) {
        rg_body b = add(&s, RG_BODY_DYNAMIC, 1 + 0.1 * i, -10 + i * 0.5, 1 + (i % 4) * 0.9);
        if (i % 2)
            assert_ok(rg_body_set_circle(s.w, b, 0.2f));
        else
            assert_ok(rg_body_set_aabb(s.w, b, 0.2f, 0.2f));
        if (i % 3 == 0) assert_ok(rg_body_set_drag(s.w, b, 0.2f, 0.05f));
        if (i % 4 == 0) assert_ok(rg_body_set_surface_friction(s.w, b, 0.3f, 2));
        if (i % 5 == 0) assert_ok(rg_body_set_speed_limits(s.w, b, 0.02f, 5));
        if (i % 6 == 0) assert_ok(rg_body_set_gravity_scale(s.w, b, 0.5f));
        if (i > 0 && i % 2 == 0) {
            uint64_t sp;
            assert_ok(rg_spring_create(s.w, b, s.b[s.n - 2], v2(0, 0), 0.6f, 40, 0.5f, &sp));
        }
        if (i % 7 == 3) {
            uint64_t sp;
            assert_ok(rg_spring_create(s.w, b, 0, v2(-10 + i * 0.5, 4), 1, 15, 0.2f, &sp));
        }
    }
    uint64_t h = 1469598103934665603ull;
    for (int k = 1; k <= 360; k++) {
        double frame = (1.0 / 60) * (0.5 + (k % 7) * 0.25);
        int32_t steps;
        if (k % 30 == 0) assert_ok(rg_body_apply_impulse(s.w, s.b[1 + k % 40], v2(1, 3)));
        if (k % 45 == 0) assert_ok(rg_body_apply_force(s.w, s.b[1 + (k * 7) % 40], v2(20, 10)));
        if (k == 100) assert_ok(rg_body_set_position(s.w, s.b[5], v2(3, 3)));
        if (k == 150) assert_ok(rg_body_destroy(s.w, s.b[8]));
        if (k == 170) assert_ok(rg_body_set_filter(s.w, s.b[12], 2, 0xFFFFFFFDu));
        if (k == 200) assert_ok(rg_body_set_sensor(s.w, s.b[14], 1));
        assert_ok(rg_world_advance(s.w, (rg_real)frame, &steps));
        if (k % 30 == 0) h = scene_hash(&s, h);
    }
    rg_world_destroy(s.w);
    return h;
}

/* Continuous collision: bullets (circles and boxes) at 50-300 m/s against thin walls and a
 * tile floor, with continuous collision on and off. */
static uint64_t run_bullets(int32_t continuous)
{
    scene s;
    s.n = 0;
    assert_ok(rg_world_create(&s.w));
    assert_ok(rg_world_set_gravity(s.w, v2(0, -9.81)));
    assert_ok(rg_world_set_continuous(s.w, continuous));
    for (int t = 0; t < 20; t++) {
        rg_body tile = add(&s, RG_BODY_STATIC, 0, -9.5 + t, -0.5);
        assert_ok(rg_body_set_aabb(s.w, tile, 0.5f, 0.5f));
    }
    rg_body wall = add(&s, RG_BODY_STATIC, 0, 8, 3);
    assert_ok(rg_body_set_aabb(s.w, wall, 0.01f, 3));
    rg_body wall2 = add(&s, RG_BODY_STATIC, 0, -8, 3);
    assert_ok(rg_body_set_aabb(s.w, wall2, 0.01f, 3));
    for (int i = 0; i < 24; i++) {
        rg_body b = add(&s, RG_BODY_DYNAMIC, 0.1 + 0.05 * i, -2 + (i % 6) * 0.7, 0.5 + (i / 6) * 1.1);
        if (i % 2)
            assert_ok(rg_body_set_circle(s.w, b, 0.05f));
        else
            assert_ok(rg_body_set_aabb(s.w, b, 0.05f, 0.05f));
        double speed = 50 + 10.0 * i;
        assert_ok(rg_body_set_velocity(s.w, b, v2(i % 4 < 2 ? speed : -speed, -(i % 3) * 20.0)));
        if (i % 5 == 0) assert_ok(rg_body_set_restitution(s.w, b, 0.8f));
    }
    uint64_t h = 1469598103934665603ull;
    for (int k = 1; k <= 240; k++) {
        assert_ok(rg_world_step(s.w, (rg_real)(1.0 / 60)));
        if (k % 20 == 0) h = scene_hash(&s, h);
    }
    rg_world_destroy(s.w);
    return h;
}

/* Prints every hash (the constants to pin) and counts mismatches; the test fails after all
 * of its scenes ran. */
static int check(const char *name, uint64_t got, uint64_t want)
{
    printf("  %-28s 0x%016llxull%s\n", name, (unsigned long long)got, got == want ? "" : "  MISMATCH");
    return got != want;
}

#ifdef RG_DOUBLE
#define PIN(f, d) (d)
#else
#define PIN(f, d) (f)
#endif

static void test_pile_with_kinematic_sensor_and_sleeping_is_pinned(void **state)
{
    (void)state;
    static const uint64_t pin[4] = {
        PIN(0x0f87e45161dedde7ull, 0x8d8e929de97cd93cull), PIN(0x974c49c489de9b4eull, 0x6cb0756e57e4a86cull),
        PIN(0xa1e85ac15d7de9f6ull, 0xd3d0a0a7c579c7e8ull), PIN(0xeebab23805c0aa23ull, 0x3bdfbeeff19f3bdaull),
    };
    static const char *names[4] = { "pile explicit", "pile semi-implicit", "pile verlet", "pile rk4" };
    int bad = 0;
    for (int integ = 0; integ < 4; integ++) bad += check(names[integ], run_pile(integ), pin[integ]);
    assert_int_equal(bad, 0);
}

static void test_forces_springs_and_accumulator_among_shapes_are_pinned(void **state)
{
    (void)state;
    static const uint64_t pin[4] = {
        PIN(0x39e6f5d53a7f7c31ull, 0x38885ad6a8bd33e6ull), PIN(0x472ac386e2a959e1ull, 0x88d41aef9fa7d73eull),
        PIN(0x8d5ca7c9b451dfd9ull, 0xa732f608d238c06full), PIN(0x3fc49d143fbbc145ull, 0x3f1360588a80f110ull),
    };
    static const char *names[4] = { "forces explicit", "forces semi-implicit", "forces verlet",
                                    "forces rk4" };
    int bad = 0;
    for (int integ = 0; integ < 4; integ++) bad += check(names[integ], run_forces(integ), pin[integ]);
    assert_int_equal(bad, 0);
}

static void test_bullets_with_and_without_continuous_collision_are_pinned(void **state)
{
    (void)state;
    int bad = check("bullets continuous", run_bullets(1), PIN(0xcefac2c261b90e04ull, 0xc03829b8782ffef2ull));
    bad += check("bullets discrete", run_bullets(0), PIN(0x2b2b17053a0ea501ull, 0xa62195048fc6b5f2ull));
    assert_int_equal(bad, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pile_with_kinematic_sensor_and_sleeping_is_pinned),
        cmocka_unit_test(test_forces_springs_and_accumulator_among_shapes_are_pinned),
        cmocka_unit_test(test_bullets_with_and_without_continuous_collision_are_pinned),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
