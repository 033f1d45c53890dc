/* test_world.c: world settings, the step's failure cases, the fixed-step accumulator, and
 * determinism. */
#include "testutil.h"

static void test_world_create_destroy_and_defaults(void **state)
{
    (void)state;
    rg_world *w = NULL;
    rg_vec2 g;
    int32_t integ, max;
    rg_real dt;
    assert_status(rg_world_create(NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_create_with_allocator(NULL, NULL, &w), RG_ERR_INVALID_ARGUMENT);
    assert_null(w);
    rg_world_destroy(NULL); /* a no-op */
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_get_gravity(w, &g));
    assert_true(g.x == 0 && g.y == 0);
    assert_ok(rg_world_get_wind(w, &g));
    assert_true(g.x == 0 && g.y == 0);
    assert_ok(rg_world_get_integrator(w, &integ));
    assert_int_equal(integ, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    assert_ok(rg_world_get_fixed_step(w, &dt, &max));
    assert_true(dt == (rg_real)(1.0 / 60));
    assert_int_equal(max, 8);
    assert_int_equal(rg_world_body_count(w), 0);
    assert_int_equal(rg_world_body_count(NULL), 0);
    rg_world_destroy(w);
}

static void test_version_status_strings_and_real_size(void **state)
{
    (void)state;
    assert_int_equal(rg_version(), RG_VERSION);
    assert_int_equal(RG_VERSION, RG_VERSION_MAJOR * 10000 + RG_VERSION_MINOR * 100 + RG_VERSION_PATCH);
    assert_int_equal(rg_real_size(), (int32_t)sizeof(rg_real));
    for (int s = -10; s <= 10; s++) {
        const char *msg = rg_status_string(s);
        assert_non_null(msg);
        assert_true(strlen(msg) > 0);
    }
    assert_string_equal(rg_status_string(RG_ERR_STALE_HANDLE), "stale or invalid handle");
}

static void test_world_setters_reject_bad_input_and_change_nothing(void **state)
{
    (void)state;
    rg_world *w;
    const rg_real nan = (rg_real)NAN, inf = (rg_real)INFINITY;
    rg_vec2 g;
    int32_t i32, steps = 42;
    rg_real r;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -9)));
    assert_ok(rg_world_set_wind(w, v2(1, 0)));
    assert_status(rg_world_set_gravity(NULL, v2(0, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_gravity(w, v2(nan, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_gravity(w, v2(0, inf)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_wind(NULL, v2(0, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_wind(w, v2(-inf, 0)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_wind(w, v2(0, nan)), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_integrator(w, -1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_integrator(w, 4), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_integrator(NULL, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_gravity(w, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_gravity(NULL, &g), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_wind(w, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_integrator(w, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_integrator(NULL, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_fixed_step(w, 0, 8), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_fixed_step(w, -1, 8), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_fixed_step(w, nan, 8), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_fixed_step(w, inf, 8), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_fixed_step(w, (rg_real)0.01, 0), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_set_fixed_step(NULL, (rg_real)0.01, 1), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_fixed_step(w, NULL, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_fixed_step(NULL, &r, &i32), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_advance(NULL, 1, &steps), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_advance(w, -1, &steps), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_advance(w, nan, &steps), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_advance(w, inf, &steps), RG_ERR_INVALID_ARGUMENT);
    assert_int_equal(steps, 42);
    assert_status(rg_world_get_alpha(w, NULL), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_get_alpha(NULL, &r), RG_ERR_INVALID_ARGUMENT);
    assert_ok(rg_world_get_gravity(w, &g));
    assert_true(g.x == 0 && g.y == -9);
    assert_ok(rg_world_get_wind(w, &g));
    assert_true(g.x == 1 && g.y == 0);
    assert_ok(rg_world_get_integrator(w, &i32));
    assert_int_equal(i32, RG_INTEGRATOR_SEMI_IMPLICIT_EULER);
    assert_ok(rg_world_get_fixed_step(w, &r, &i32));
    assert_true(r == (rg_real)(1.0 / 60) && i32 == 8);
    assert_ok(rg_world_get_alpha(w, &r));
    assert_true(r == 0);
    rg_world_destroy(w);
}

static void test_step_rejects_bad_dt_and_changes_nothing(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -10)));
    rg_body b = make_body(w, 1, 0, 0);
    assert_ok(rg_body_apply_force(w, b, v2(5, 0)));
    const rg_real bad[] = { 0, -1, (rg_real)NAN, (rg_real)INFINITY, (rg_real)-INFINITY };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_status(rg_world_step(w, bad[i]), RG_ERR_INVALID_ARGUMENT);
    assert_status(rg_world_step(NULL, 1), RG_ERR_INVALID_ARGUMENT);
    rg_vec2 p = pos_of(w, b), v = vel_of(w, b);
    assert_true(p.x == 0 && p.y == 0 && v.x == 0 && v.y == 0);
    /* the applied force survived the refused steps and acts on the next real one */
    assert_ok(rg_world_step(w, 1));
    v = vel_of(w, b);
    assert_true(v.x == 5 && v.y == -10);
    rg_world_destroy(w);
}

/* An empty world, and one with only static bodies, step and advance with every integrator
 * (the body arrays do not exist yet: nothing may touch them). */
static void test_empty_and_static_only_worlds_step(void **state)
{
    (void)state;
    for (int statics = 0; statics <= 1; statics++) {
        for (int integ = 0; integ <= 3; integ++) {
            rg_world *w;
            rg_body s = 0;
            int32_t steps;
            assert_ok(rg_world_create(&w));
            assert_ok(rg_world_set_integrator(w, integ));
            assert_ok(rg_world_set_gravity(w, v2(0, -10)));
            if (statics) assert_ok(rg_body_create(w, RG_BODY_STATIC, 0, v2(1, 1), &s));
            assert_ok(rg_world_step(w, (rg_real)0.01));
            assert_ok(rg_world_advance(w, (rg_real)0.05, &steps));
            assert_int_equal(steps, 3);
            if (statics) {
                rg_vec2 p = pos_of(w, s);
                assert_true(p.x == 1 && p.y == 1);
            }
            rg_world_destroy(w);
        }
    }
}

/* A jumping body with drag and a spring, so that every stage of the step matters. */
static rg_world *jump_scene(int integrator, rg_body *out)
{
    rg_world *w;
    uint64_t s;
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_integrator(w, integrator));
    assert_ok(rg_world_set_gravity(w, v2(0, -9.81)));
    assert_ok(rg_world_set_wind(w, v2(0.5, 0)));
    *out = make_body(w, 1.3, 0, 0);
    assert_ok(rg_body_set_velocity(w, *out, v2(3, 7)));
    assert_ok(rg_body_set_drag(w, *out, 0.05f, 0.02f));
    rg_body c = make_body(w, 0.7, 2, 0);
    assert_ok(rg_spring_create(w, c, 0, v2(2, 1), 0.5f, 30, 0.2f, &s));
    return w;
}

/* Bit-identical results after the same number of fixed steps, whatever the frame rate
 * (30, 60, 144 Hz) or jitter fed the accumulator. */
static void test_accumulator_gives_the_same_trajectory_at_any_frame_rate(void **state)
{
    (void)state;
    enum { STEPS = 240 };
    const rg_real dt = (rg_real)(1.0 / 60);
    for (int integ = 0; integ <= 3; integ++) {
        rg_vec2 ref[STEPS + 1];
        rg_body b;
        rg_world *w = jump_scene(integ, &b);
        ref[0] = pos_of(w, b);
        for (int i = 1; i <= STEPS; i++) {
            assert_ok(rg_world_step(w, dt));
            ref[i] = pos_of(w, b);
        }
        rg_world_destroy(w);
        const double rates[] = { 30, 60, 144, 0 /* jitter */ };
        for (size_t r = 0; r < 4; r++) {
            w = jump_scene(integ, &b);
            unsigned seed = 12345;
            int total = 0;
            while (total < STEPS) {
                double frame;
                if (rates[r] > 0) {
                    frame = 1 / rates[r];
                } else {
                    seed = seed * 1103515245u + 12345u;
                    frame = 0.004 + 0.03 * (double)((seed >> 16) & 0x7fff) / 32767.0;
                }
                int32_t steps = -1;
                assert_ok(rg_world_advance(w, (rg_real)frame, &steps));
                assert_true(steps >= 0 && steps <= 8);
                total += steps;
                if (total > STEPS) break;
                rg_vec2 p = pos_of(w, b);
                if (memcmp(&p, &ref[total], sizeof p) != 0)
                    fail_msg("integrator %d, rate %g: differs after %d steps", integ, rates[r], total);
            }
            rg_world_destroy(w);
        }
    }
}

static void test_cap_on_steps_stops_a_spiral_of_death(void **state)
{
    (void)state;
    rg_body b;
    rg_world *w = jump_scene(RG_INTEGRATOR_SEMI_IMPLICIT_EULER, &b);
    int32_t steps = 0;
    rg_real alpha;
    assert_ok(rg_world_set_fixed_step(w, (rg_real)0.01, 5));
    assert_ok(rg_world_advance(w, 10, &steps)); /* a 10 s hitch */
    assert_int_equal(steps, 5);
    assert_ok(rg_world_get_alpha(w, &alpha));
    assert_true(alpha >= 0 && alpha < 1); /* the excess was dropped, not queued */
    assert_ok(rg_world_advance(w, 0, &steps));
    assert_int_equal(steps, 0);
    assert_ok(rg_world_advance(w, (rg_real)0.0105, &steps));
    assert_true(steps <= 2);
    assert_ok(rg_world_advance(w, (rg_real)1e30, NULL)); /* huge but finite: still capped */
    rg_world_destroy(w);
}

/* alpha = leftover / dt, and the interpolated position blends the positions before and
 * after the last step; a teleport or a direct step shows the current position, and so does
 * a state that owes steps (alpha >= 1). */
static void test_alpha_and_interpolated_position(void **state)
{
    (void)state;
    rg_world *w;
    assert_ok(rg_world_create(&w));
    rg_body b = make_body(w, 1, 0, 0);
    assert_ok(rg_body_set_velocity(w, b, v2(1, -2)));
    assert_ok(rg_world_set_fixed_step(w, (rg_real)0.25, 8));
    int32_t steps;
    rg_real alpha;
    rg_vec2 ip;
    assert_ok(rg_world_advance(w, (rg_real)0.625, &steps)); /* 2 steps, 0.125 left */
    assert_int_equal(steps, 2);
    assert_ok(rg_world_get_alpha(w, &alpha));
    assert_near(alpha, 0.5, 4 * REAL_EPS);
    assert_ok(rg_body_get_interpolated_position(w, b, &ip));
    /* before the last step x = 0.25, after it x = 0.5: halfway is 0.375 */
    assert_near(ip.x, 0.375, 8 * REAL_EPS);
    assert_near(ip.y, -0.75, 8 * REAL_EPS);
    /* a shorter fixed step keeps the time held: 0.125 s is 12.5 steps of 0.01 owed, alpha
     * says so, and the position drawn is the current one, not 12.5 steps ahead of it */
    assert_ok(rg_world_set_fixed_step(w, (rg_real)0.01, 8));
    assert_ok(rg_world_get_alpha(w, &alpha));
    assert_near(alpha, 12.5, 32 * REAL_EPS);
    assert_ok(rg_body_get_interpolated_position(w, b, &ip));
    rg_vec2 now = pos_of(w, b);
    assert_true(ip.x == now.x && ip.y == now.y);
    assert_ok(rg_world_advance(w, 0, &steps)); /* the owed steps, 8 at most */
    assert_int_equal(steps, 8);
    assert_ok(rg_world_set_fixed_step(w, (rg_real)0.25, 8));
    assert_ok(rg_body_set_position(w, b, v2(10, 10)));
    assert_ok(rg_body_get_interpolated_position(w, b, &ip));
    assert_true(ip.x == 10 && ip.y == 10);
    assert_ok(rg_world_step(w, (rg_real)0.25));
    assert_ok(rg_body_get_interpolated_position(w, b, &ip));
    rg_vec2 p = pos_of(w, b);
    assert_true(ip.x == p.x && ip.y == p.y);
    rg_world_destroy(w);
}

/* FNV-1a over every body's position and velocity (testutil.h's fnv: either byte order). */
static uint64_t state_hash(rg_world *w, const rg_body *bodies, int n)
{
    uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < n; i++) {
        rg_vec2 pv[2] = { pos_of(w, bodies[i]), vel_of(w, bodies[i]) };
        h = fnv(h, pv, 4, sizeof pv[0].x);
    }
    return h;
}

static uint64_t run_determinism_scene(void)
{
    enum { N = 64 };
    rg_world *w;
    rg_body b[N];
    assert_ok(rg_world_create(&w));
    assert_ok(rg_world_set_gravity(w, v2(0, -9.81)));
    assert_ok(rg_world_set_wind(w, v2(0.3, 0.1)));
    for (int i = 0; i < N; i++) {
        b[i] = make_body(w, 0.5 + 0.1 * i, i % 8, i / 8);
        assert_ok(rg_body_set_velocity(w, b[i], v2(i % 5 - 2, i % 7)));
        if (i % 3 == 0) assert_ok(rg_body_set_drag(w, b[i], 0.1f, 0.05f));
        if (i % 4 == 0) assert_ok(rg_body_set_surface_friction(w, b[i], 0.3f, 2));
        if (i % 5 == 0) assert_ok(rg_body_set_speed_limits(w, b[i], 0.05f, 6));
        if (i > 0 && i % 2 == 0) {
            uint64_t s;
            assert_ok(rg_spring_create(w, b[i], b[i - 1], v2(0, 0), 1, 20, 0.3f, &s));
        }
    }
    for (int integ = 0; integ <= 3; integ++) {
        assert_ok(rg_world_set_integrator(w, integ));
        for (int k = 0; k < 60; k++) {
            if (k % 10 == 0) assert_ok(rg_body_apply_force(w, b[k % N], v2(3, 1)));
            assert_ok(rg_world_step(w, (rg_real)(1.0 / 60)));
        }
    }
    uint64_t h = state_hash(w, b, N);
    rg_world_destroy(w);
    return h;
}

/* The state matches the hash recorded for this build type, so a change of any
 * optimisation level, compiler flag or code path that alters a single bit shows up here
 * (update the constant only for an intended change of results).  Collision scenes are
 * pinned in test_determinism.c. */
static void test_same_scene_gives_identical_bytes(void **state)
{
    (void)state;
    uint64_t h1 = run_determinism_scene();
    printf("determinism hash: 0x%016llx\n", (unsigned long long)h1);
#ifdef RG_DOUBLE
    const uint64_t expected = 0xba27f065b289d97dull;
#else
    const uint64_t expected = 0x1225732de11ca232ull;
#endif
    assert_true(h1 == expected);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_world_create_destroy_and_defaults),
        cmocka_unit_test(test_version_status_strings_and_real_size),
        cmocka_unit_test(test_world_setters_reject_bad_input_and_change_nothing),
        cmocka_unit_test(test_step_rejects_bad_dt_and_changes_nothing),
        cmocka_unit_test(test_empty_and_static_only_worlds_step),
        cmocka_unit_test(test_accumulator_gives_the_same_trajectory_at_any_frame_rate),
        cmocka_unit_test(test_cap_on_steps_stops_a_spiral_of_death),
        cmocka_unit_test(test_alpha_and_interpolated_position),
        cmocka_unit_test(test_same_scene_gives_identical_bytes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
